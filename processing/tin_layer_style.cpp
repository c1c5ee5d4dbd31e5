// SPDX-License-Identifier: GPL-3.0-or-later
#include "tin_layer_style.h"

#include <qgsfillsymbol.h>
#include <qgslayertree.h>
#include <qgsproject.h>
#include <qgsmarkersymbol.h>
#include <qgssinglesymbolrenderer.h>
#include <qgsvectorlayer.h>

#include <QFileInfo>

namespace tinlod::qgis {

void TinLayerStyle::postProcessLayer(QgsMapLayer* layer, QgsProcessingContext& context, QgsProcessingFeedback*) {
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
  if (!group_.isEmpty()) moveIntoGroup(layer, context);
}

void TinLayerStyle::moveIntoGroup(QgsMapLayer* layer, QgsProcessingContext& context) const {
  QgsProject* project = context.project();
  if (!project) return;
  QgsLayerTreeGroup* root = project->layerTreeRoot();
  QgsLayerTreeLayer* node = root->findLayer(layer);
  if (!node) return;
  QgsLayerTreeGroup* group = root->findGroup(group_);
  if (!group) group = root->insertGroup(0, group_);
  int index = 0;  // after the layers of lower order already there
  for (QgsLayerTreeNode* child : group->children())
    if (child->customProperty(QStringLiteral("tinlod/order")).toInt() < order_) ++index;
  QgsLayerTreeLayer* moved = group->insertLayer(index, layer);
  moved->setCustomProperty(QStringLiteral("tinlod/order"), order_);
  moved->setItemVisibilityChecked(visible_);
  if (QgsLayerTreeGroup* parent = qobject_cast<QgsLayerTreeGroup*>(node->parent())) parent->removeChildNode(node);
}

void loadTinLayerOnCompletion(QgsProcessingContext& context, const QString& gpkg, const QString& layerName,
                              const QString& outputName, const QString& group, bool visible, int order) {
  const QString name = group.isEmpty() ? QStringLiteral("%1 %2").arg(QFileInfo(gpkg).completeBaseName(), layerName) : layerName;
  QgsProcessingContext::LayerDetails details(name, context.project(), outputName, QgsProcessingUtils::LayerHint::Vector);
  details.setPostProcessor(new TinLayerStyle(group, visible, order));
  context.addLayerToLoadOnCompletion(gpkg + QStringLiteral("|layername=") + layerName, details);
}

}  // namespace tinlod::qgis
