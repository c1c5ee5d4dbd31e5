// SPDX-License-Identifier: GPL-3.0-or-later
// Private: whether a counter-clockwise triangle holds a point in x/y, by CGAL's exact
// orientation. Closed: a point on an edge or a corner is inside, so triangles that
// share edges leave no gaps between them.
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace tinlod {

using ExactPoint2 = CGAL::Exact_predicates_inexact_constructions_kernel::Point_2;

inline bool triangleContains(const ExactPoint2& a, const ExactPoint2& b, const ExactPoint2& c, const ExactPoint2& p) {
  return CGAL::orientation(a, b, p) != CGAL::RIGHT_TURN && CGAL::orientation(b, c, p) != CGAL::RIGHT_TURN &&
         CGAL::orientation(c, a, p) != CGAL::RIGHT_TURN;
}

}  // namespace tinlod
