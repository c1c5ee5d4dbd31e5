// SPDX-License-Identifier: GPL-3.0-or-later
// Private: which geometries count as points, for every input that takes points (locate's
// points, build's -fixed_points, lod's -centers). A line or polygon given by mistake is
// refused with its type named, rather than read as no point or as every point outside.
#pragma once

#include <ogrsf_frmts.h>

#include <array>
#include <string>
#include <vector>

namespace tinlod {

// Refuses a layer declared to hold another geometry type, or none, before any feature is
// read. A layer of mixed types passes: its features are checked one by one.
void checkPointLayer(OGRLayer& layer, const std::string& what, const std::string& path);

// The points of one feature: its point, or each point of a multipoint; none when it has
// no geometry or an empty one. Throws Error naming the feature for any other type.
void appendPoints(const OGRFeature& feature, const std::string& what, const std::string& path,
                  std::vector<std::array<double, 2>>& out);

}  // namespace tinlod
