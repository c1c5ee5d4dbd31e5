// SPDX-License-Identifier: GPL-3.0-or-later
#include "vertex_index_parameter.h"

namespace tinlod::qgis {

QgsProcessingParameterDefinition* vertexIndexParameter() {
  auto* p = new QgsProcessingParameterBoolean(QStringLiteral("VERTEX_INDEX"), QStringLiteral("Spatial index on the vertices layer"),
                                              false);
  p->setFlags(p->flags() | QgsProcessingParameterDefinition::FlagAdvanced);
  return p;
}

}  // namespace tinlod::qgis
