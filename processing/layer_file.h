// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <QString>

#include <string>

class QgsVectorLayer;

namespace tinlod::qgis {

// The file behind a vector layer parameter, with its |layername=, which the core reads
// with GDAL. Throws QgsProcessingException naming `parameter` when the layer is missing or
// not stored in such a file; `kind` says what layer is wanted ("a point layer").
std::string layerFile(const QgsVectorLayer* layer, const QString& parameter, const QString& kind);

}  // namespace tinlod::qgis
