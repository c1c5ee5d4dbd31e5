// SPDX-License-Identifier: GPL-3.0-or-later
#include "tin_layer_output.h"

#include <algorithm>

namespace tinlod::qgis {

QgsProcessingOutputVectorLayer* trianglesLayerOutput(const QString& name, const QString& description) {
  return new QgsProcessingOutputVectorLayer(name, description, QgsProcessing::TypeVectorPolygon);
}

QString gpkgLayer(const QString& gpkg, const QString& layer) { return gpkg + QStringLiteral("|layername=") + layer; }

QString hierarchyLevelLayer(const QString& gpkg, std::int32_t level, const std::vector<std::int32_t>& views) {
  if (std::find(views.begin(), views.end(), level) != views.end()) return gpkgLayer(gpkg, QStringLiteral("level_%1").arg(level));
  return gpkgLayer(gpkg, QStringLiteral("triangles")) +
         QStringLiteral("|subset=\"first_level\" <= %1 AND \"last_level\" >= %1").arg(level);
}

}  // namespace tinlod::qgis
