// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <string>
#include <vector>


namespace tinlod {

struct Point3 {
  double x = 0, y = 0, z = 0;
};

// How a vertex's importance is measured; the least important vertices go first.
enum class Measure { Degree, Volume, Normal, Error };

std::string measureName(Measure measure);
Measure parseMeasure(const std::string& name);  // throws Error listing the choices

// A vertex and its neighbours in counter-clockwise order: its star in the TIN. An open
// star (a vertex on the outline) has a triangle between each ring vertex and the next but
// none between the last and the first: its deletion joins those two by an outline edge.
struct Star {
  Point3 centre;
  std::vector<Point3> ring;
  bool open = false;
};

using LocalTriangle = std::array<int, 3>;  // indices into Star::ring, counter-clockwise

// The Delaunay triangulation of the star's polygon without its centre, by Devillers'
// ear queue: repeatedly cut the convex ear whose circumcircle has the greatest power with
// respect to the centre (the centre is inside every such circle; the Delaunay ear's is
// the one it is least inside). The ranking uses floating point; each ear is then
// confirmed with CGAL's exact orientation and in-circle tests (no other polygon vertex
// strictly inside its circle), so the result is always a Delaunay triangulation of the
// polygon: CGAL's own removal makes the same one, up to the choice among cocircular
// points (checked in the tests). The simplifier deletes vertices with it. `out` is the
// caller's, to spare allocations. An open star's polygon (its ring, closed by the edge
// from the last ring vertex to the first) is filled by retriangulateOpenStar. Returns
// false, with `out` empty, when an open star's polygon cannot be filled (see there).
bool retriangulateStar(const Star& star, std::vector<LocalTriangle>& out);
std::vector<LocalTriangle> retriangulateStar(const Star& star);
// The constrained Delaunay triangulation of an open star's polygon: ears clipped with
// CGAL's exact orientation, then edges flipped until each inner edge passes CGAL's exact
// in-circle test (Lawson). The new outline edge joins the last ring vertex to the first;
// every other ring vertex must lie strictly on its inner side, so that the polygon is
// simple, or false is returned and nothing is filled.
bool retriangulateOpenStar(const Star& star, std::vector<LocalTriangle>& out);
// For each ring edge k of a star of degree d (ring vertex k to k + 1), the index among
// `fill` (its d - 2 triangles, as retriangulateStar makes them) of the triangle on it.
void ringEdgeTriangles(const LocalTriangle* fill, int d, int* onEdge);

// |volume under the star - volume under its retriangulation| (cubic metres). For an open
// star the ground it gives up (between the old and the new outline edge) counts as the
// plane through the vertex and its two outline neighbours, so that only the change over
// the ground both cover is measured.
double volumeChange(const Star& star, const std::vector<LocalTriangle>& without);

// Mean dot product of the star triangles' unit normals with their normalised mean: 1 on
// a plane, less where the star bends.
double normalFlatness(const Star& star);

// Whether d lies strictly inside the circle through a, b, c (counter-clockwise), by CGAL's
// exact in-circle predicate.
bool strictlyInCircle(const Point3& a, const Point3& b, const Point3& c, const Point3& d);

// The measure's importance of the star's centre: degree (ring vertices), volume change or
// 1 - flatness; the error measure is the simplifier's, measured against the DEM's cells.
// Smaller means less important. The volume of an interior star is measured on the ear
// queue in floating point alone (ranking, and convexity by CGAL's floating-point kernel:
// a near-degenerate star can change the value, never a TIN); an open star's on its exact
// fill, and +infinity when it cannot be filled.
double importance(Measure measure, const Star& star);

}  // namespace tinlod
