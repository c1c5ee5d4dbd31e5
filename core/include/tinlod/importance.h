// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <string>
#include <vector>

#include "tinlod/triangle_plane.h"

namespace tinlod {

struct Point3 {
  double x = 0, y = 0, z = 0;
};

// How a vertex's importance is measured; the least important vertices go first.
enum class Measure { Degree, Volume, Normal, Error };

std::string measureName(Measure measure);
Measure parseMeasure(const std::string& name);  // throws Error listing the choices

// A vertex and its neighbours in counter-clockwise order: its star in the TIN.
struct Star {
  Point3 centre;
  std::vector<Point3> ring;
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
// caller's, to spare allocations. Returns convexRing(star), which the queue finds on the
// way.
bool retriangulateStar(const Star& star, std::vector<LocalTriangle>& out);
std::vector<LocalTriangle> retriangulateStar(const Star& star);
// For each ring edge k of a star of degree d (ring vertex k to k + 1), the index among
// `fill` (its d - 2 triangles, as retriangulateStar makes them) of the triangle on it.
void ringEdgeTriangles(const LocalTriangle* fill, int d, int* onEdge);

// |volume under the star - volume under its retriangulation| (cubic metres).
double volumeChange(const Star& star, const std::vector<LocalTriangle>& without);

// Mean dot product of the star triangles' unit normals with their normalised mean: 1 on
// a plane, less where the star bends.
double normalFlatness(const Star& star);

// Whether the star's ring is a convex polygon (CGAL's exact orientation).
bool convexRing(const Star& star);
// One of `count` triangles, which triangulate the star's polygon, that holds p in x/y
// (CGAL's exact orientation): triangle `likely` if it does, else the first that does (on
// a shared edge, the first). p must lie in the polygon (closed), as the samples under a
// star do; `convex` is convexRing(star), which spares the tests on the ring's edges.
// A sample under old star triangle k most often lies in the new triangle on ring edge k:
// tried first, it spares most tests.
int triangleHolding(const Star& star, const LocalTriangle* tris, std::size_t count, const Point3& p, bool convex,
                    int likely = -1);
// The plane of triangle t of the star's ring, from its first corner.
TrianglePlane planeOf(const Star& star, const LocalTriangle& t);

// Largest vertical distance from the retriangulated star to the samples (which must
// lie in the star's polygon) and to the centre itself.
double maxVerticalError(const Star& star, const std::vector<LocalTriangle>& without,
                        const std::vector<Point3>& samples);

// The measure's importance of the star's centre: degree, volume change, 1 - flatness,
// or vertical error. Smaller means less important. The volume is measured on the ear
// queue in floating point alone (ranking, and convexity by CGAL's floating-point kernel:
// a near-degenerate star can change the value, never a TIN); the error on the exact
// retriangulation, so that it is the error the deletion certifies.
double importance(Measure measure, const Star& star, const std::vector<Point3>& samples);

}  // namespace tinlod
