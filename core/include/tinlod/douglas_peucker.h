// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace tinlod {

using LinePoint = std::array<double, 2>;
using Polyline = std::vector<LinePoint>;

// The Douglas-Peucker simplification value of every vertex: the endpoints get infinity;
// then, within the stretch between two kept vertices a and b, the vertex farthest from
// the segment ab gets the smaller of that distance and the values of a and b, and both
// halves are treated the same way. So the simplification at any threshold t keeps
// exactly the vertices whose value exceeds t, as Douglas-Peucker with tolerance t does.
// Iterative (no recursion depth limit); O(n log n) for most lines, O(n^2) at worst.
std::vector<double> douglasPeuckerValues(const Polyline& line);

// The line simplified at `threshold`: the vertices whose value exceeds it. O(n).
Polyline simplified(const Polyline& line, const std::vector<double>& values, double threshold);

// Pairs of segments of different lines that touch or cross (CGAL's exact test): the
// crossings that simplification can bring to contour lines that never met.
std::size_t crossingCount(const std::vector<Polyline>& lines);

}  // namespace tinlod
