// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the CGAL typedef chain. Only triangulation code includes this header, so
// CGAL stays an implementation detail (and its compile cost stays in few files).
#pragma once

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Projection_traits_xy_3.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <cstdint>

#include <vector>

#include "tinlod/feedback.h"
#include "tinlod/tin.h"

namespace tinlod::cgal {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
// Delaunay in x/y with z carried along: a 2.5D terrain.
using Traits = CGAL::Projection_traits_xy_3<Kernel>;
// What a vertex is to tinlod: its id, and the simplifier's per-vertex state kept on the
// vertex itself, where the circulators already are (side arrays indexed by id would be
// read in random order).
struct VertexTag {
  VertexId id = 0;
  std::uint32_t rank = 0;      // position in the spatial insertion order: a memory-friendly order
  std::int32_t stamp = -1;     // the level in which the vertex or a neighbour was selected
  bool fixed = false;
  bool stale = true;           // its importance must be recomputed
  double importance = 0;
};
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<VertexTag, Traits>;
// What a face is to tinlod. The default marks a face CGAL has just created.
struct FaceTag {
  static constexpr std::int32_t kFresh = -2;    // created by CGAL, not yet numbered
  static constexpr std::int32_t kOutside = -1;  // over nodata or outside the convex hull of data
  static constexpr std::int32_t kDying = -3;    // in the star of a vertex being removed
  std::int32_t id = kFresh;                     // >= 0: a triangle of the TIN
};
// Faces carry their tag, so adjacency and membership are read without lookup tables.
using FaceBase = CGAL::Triangulation_face_base_with_info_2<FaceTag, Traits>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Traits, Tds>;
using Point = Traits::Point_2;
using VertexHandle = Delaunay::Vertex_handle;
using FaceHandle = Delaunay::Face_handle;

// Inserts every vertex (id = index), spatially sorted, reporting progress; vertices at
// an x/y already taken keep no handle. Returns the handle of each vertex.
std::vector<VertexHandle> insertVertices(Delaunay& dt, const std::vector<TinVertex>& vertices,
                                         const ProgressRange& progress);

}  // namespace tinlod::cgal
