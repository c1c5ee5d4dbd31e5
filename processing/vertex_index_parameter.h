// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <qgsprocessingparameters.h>

namespace tinlod::qgis {

// VERTEX_INDEX: an advanced yes/no, off by default, for a spatial index on the vertices
// layer of the TIN a tool writes (the core's -vertex_index); the same for every tool.
QgsProcessingParameterDefinition* vertexIndexParameter();

}  // namespace tinlod::qgis
