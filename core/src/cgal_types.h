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
// What a vertex is to tinlod: its id in the TIN.
struct VertexTag {
  VertexId id = 0;
};
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<VertexTag, Traits>;
// What a face is to tinlod: its triangle's index, or a negative mark.
struct FaceTag {
  std::int32_t id = -1;
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
