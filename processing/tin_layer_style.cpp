// SPDX-License-Identifier: GPL-3.0-or-later
#include "tin_layer_style.h"

#include <qgsfillsymbol.h>
#include <qgsmarkersymbol.h>
#include <qgssinglesymbolrenderer.h>
#include <qgsvectorlayer.h>

#include <QFileInfo>

namespace tinlod::qgis {

void TinLayerStyle::postProcessLayer(QgsMapLayer* layer, QgsProcessingContext&, QgsProcessingFeedback*) {
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
}

void loadTinLayerOnCompletion(QgsProcessingContext& context, const QString& gpkg, const QString& layerName,
                              const QString& outputName) {
  QgsProcessingContext::LayerDetails details(QStringLiteral("%1 %2").arg(QFileInfo(gpkg).completeBaseName(), layerName),
                                             context.project(), outputName, QgsProcessingUtils::LayerHint::Vector);
  details.setPostProcessor(new TinLayerStyle());
  context.addLayerToLoadOnCompletion(gpkg + QStringLiteral("|layername=") + layerName, details);
}

}  // namespace tinlod::qgis
