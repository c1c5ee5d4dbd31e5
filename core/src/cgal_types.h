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

#include "tinlod/tin.h"

namespace tinlod::cgal {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
// Delaunay in x/y with z carried along: a 2.5D terrain.
using Traits = CGAL::Projection_traits_xy_3<Kernel>;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<VertexId, Traits>;
// Faces carry their index in the output, so adjacency is read without a lookup table.
using FaceBase = CGAL::Triangulation_face_base_with_info_2<std::int32_t, Traits>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Traits, Tds>;
using Point = Traits::Point_2;

}  // namespace tinlod::cgal
