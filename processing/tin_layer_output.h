// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <qgsprocessingoutputs.h>

#include <QString>

#include <cstdint>
#include <vector>

namespace tinlod::qgis {

// A GeoPackage given to a vector input gives QGIS its first table: a TIN's vertices, where a
// model's next step (native:centroids, a clip) wants the triangles. These outputs name the
// layer itself, "tin.gpkg|layername=triangles", for a model or a script to pass on.
QgsProcessingOutputVectorLayer* trianglesLayerOutput(const QString& name, const QString& description);

QString gpkgLayer(const QString& gpkg, const QString& layer);

// A hierarchy's level as a layer: its level_N view, or where LEVEL_VIEWS wrote none for it,
// the triangles table cut to the level as the view would be.
QString hierarchyLevelLayer(const QString& gpkg, std::int32_t level, const std::vector<std::int32_t>& views);

}  // namespace tinlod::qgis
