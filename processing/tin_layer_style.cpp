// SPDX-License-Identifier: GPL-3.0-or-later
#include "tin_layer_style.h"

#include <qgsfillsymbol.h>
#include <qgslayertree.h>
#include <qgsprocessingutils.h>
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
  place(layer, context);
}

void TinLayerStyle::place(QgsMapLayer* layer, QgsProcessingContext& context) const {
  QgsProject* project = context.project();
  if (!project) return;
  QgsLayerTreeGroup* root = project->layerTreeRoot();
  QgsLayerTreeLayer* node = root->findLayer(layer);
  if (!node) return;
  auto* parent = qobject_cast<QgsLayerTreeGroup*>(node->parent());
  QgsLayerTreeGroup* target = parent ? parent : root;
  int index = -1;  // where the layer goes in `target`; -1: it stays where QGIS put it
  if (!group_.isEmpty()) {
    target = root->findGroup(group_);
    if (!target) {
      target = root->insertGroup(0, group_);
      target->setCustomProperty(QStringLiteral("tinlod/group"), true);
    }
    index = 0;  // after the layers of lower order already there
    for (QgsLayerTreeNode* child : target->children())
      if (child != node && child->customProperty(QStringLiteral("tinlod/order")).toInt() < order_) ++index;
  } else if (parent && parent->customProperty(QStringLiteral("tinlod/group")).toBool()) {
    // QGIS adds a layer beside the current one: after a hierarchy, that is inside its
    // group of levels, where another tool's output does not belong.
    target = root, index = 0;
  }
  QgsLayerTreeLayer* placed = node;
  if (index >= 0) {
    placed = target->insertLayer(index, layer);
    if (parent) parent->removeChildNode(node);
  }
  placed->setCustomProperty(QStringLiteral("tinlod/order"), order_);
  placed->setItemVisibilityChecked(visible_);
}

QString outputBaseName(const QString& path, const QString& temporaryName) {
  const QFileInfo file(path);
  // A temporary output is named after the parameter ("OUTPUT.gpkg" in a folder of QGIS's).
  if (file.absolutePath().startsWith(QFileInfo(QgsProcessingUtils::tempFolder()).absoluteFilePath())) return temporaryName;
  return file.completeBaseName();
}

void loadTinLayerOnCompletion(QgsProcessingContext& context, const QString& gpkg, const QString& layerName,
                              const QString& outputName, const QString& baseName, const QString& group, bool visible,
                              int order) {
  const QString name = group.isEmpty() ? QStringLiteral("%1 %2").arg(baseName, layerName) : layerName;
  QgsProcessingContext::LayerDetails details(name, context.project(), outputName, QgsProcessingUtils::LayerHint::Vector);
  details.setPostProcessor(new TinLayerStyle(group, visible, order));
  context.addLayerToLoadOnCompletion(gpkg + QStringLiteral("|layername=") + layerName, details);
}

}  // namespace tinlod::qgis
