// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <string>

#include "tinlod/feedback.h"
#include "tinlod/hierarchy.h"
#include "tinlod/hierarchy_info.h"

namespace tinlod {

// A tinlod GeoPackage read back: a hierarchy, or a plain TIN as a hierarchy of one
// level. Fills the base TIN (vertices by id, level-0 triangles, CRS), every triangle
// with its levels, groups and error, the groups with their accept and reject triangles
// (not their outlines: `rings` stays empty), the vertex levels, the level statistics and
// the method's options. Throws Error when the file is not tinlod's.
struct StoredHierarchy {
  HierarchyInfo info;
  Hierarchy hierarchy;
};
StoredHierarchy readHierarchy(const std::string& path, const ProgressRange& progress);

}  // namespace tinlod
