// SPDX-License-Identifier: GPL-3.0-or-later
// Private: what `tinlod info` says of a tinlod-tiles catalogue.
#pragma once

#include "tinlod/hierarchy_info.h"

namespace tinlod {

// Adds the catalogue's tiles and its finished tiles' levels to `info`, which holds the
// catalogue's path, metadata and CRS. Only the tiles' levels tables are read, so that a
// catalogue of thousands of tiles is described in seconds.
void addCatalogueContents(HierarchyInfo& info);

}  // namespace tinlod
