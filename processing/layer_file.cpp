// SPDX-License-Identifier: GPL-3.0-or-later
#include "layer_file.h"

#include <qgsexception.h>
#include <qgsvectorlayer.h>

namespace tinlod::qgis {

std::string layerFile(const QgsVectorLayer* layer, const QString& parameter, const QString& kind) {
  if (!layer || layer->providerType() != QLatin1String("ogr"))
    throw QgsProcessingException(QStringLiteral("%1 must be %2 stored in a file GDAL reads (GeoPackage, Shapefile, GeoJSON ...): "
                                                "save it to a file first")
                                     .arg(parameter, kind));
  return layer->source().toStdString();
}

}  // namespace tinlod::qgis
