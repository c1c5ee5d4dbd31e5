// SPDX-License-Identifier: GPL-3.0-or-later
#include "tin_layer_style.h"

#include <qgsfillsymbol.h>
#include <qgsproject.h>
#include <qgsmarkersymbol.h>
#include <qgssinglesymbolrenderer.h>
#include <qgsvectorlayer.h>

#include <QFileInfo>

#include "layer_placement.h"
#include "tin_layer_output.h"
#include "stale_layers.h"

namespace tinlod::qgis {

void TinLayerStyle::postProcessLayer(QgsMapLayer* layer, QgsProcessingContext& context, QgsProcessingFeedback*) {
  removeLayersOfTablesGone(layer, context.project());
  if (reloadedIfLoadedBefore(layer)) return;
  auto* vector = qobject_cast<QgsVectorLayer*>(layer);
  if (!vector) return;
  if (vector->geometryType() == QgsWkbTypes::PolygonGeometry) {
    vector->setRenderer(new QgsSingleSymbolRenderer(QgsFillSymbol::createSimple(
        {{"color", "180,200,220,60"}, {"outline_color", "60,70,80,200"}, {"outline_width", "0.06"}})));
  } else if (vector->geometryType() == QgsWkbTypes::PointGeometry) {
    vector->setRenderer(new QgsSingleSymbolRenderer(QgsMarkerSymbol::createSimple(
        {{"name", "circle"}, {"color", "200,60,40"}, {"size", "0.8"}, {"outline_style", "no"}})));
  }
  vector->triggerRepaint();
  placeLayer(layer, context.project(), group_, order_, visible_);
}

QString outputBaseName(const QString& path, const QString& temporaryName) {
  // A temporary output is named after the parameter ("OUTPUT.gpkg" in a folder of QGIS's).
  if (inTemporaryFolder(path)) return temporaryName;
  return QFileInfo(path).completeBaseName();
}

void loadTinLayerOnCompletion(QgsProcessingContext& context, const QString& gpkg, const QString& layerName,
                              const QString& outputName, const QString& baseName, const QString& group, bool visible,
                              int order) {
  const QString name = group.isEmpty() ? QStringLiteral("%1 %2").arg(baseName, layerName) : layerName;
  context.addLayerToLoadOnCompletion(
      gpkgLayer(gpkg, layerName),
      placedLayerDetails(name, context.project(), outputName, new TinLayerStyle(group, visible, order)));
}

void loadTinOnCompletion(QgsProcessingContext& context, const QString& gpkg, const QString& baseName) {
  loadTinLayerOnCompletion(context, gpkg, QStringLiteral("vertices"), QStringLiteral("OUTPUT"), baseName, QString(), false);
  loadTinLayerOnCompletion(context, gpkg, QStringLiteral("triangles"), QStringLiteral("OUTPUT"), baseName);
}

}  // namespace tinlod::qgis
