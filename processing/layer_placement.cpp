// SPDX-License-Identifier: GPL-3.0-or-later
#include "layer_placement.h"

#include <qgslayertree.h>
#include <qgslayertreeregistrybridge.h>
#include <qgsproject.h>

#include <QFileInfo>

namespace tinlod::qgis {
namespace {

const QString kOurGroup = QStringLiteral("tinlod/group");
const QString kOrder = QStringLiteral("tinlod/order");
const QString kLoaded = QStringLiteral("tinlod/loaded");  // on a layer: placed (and styled) by a run

QgsLayerTreeGroup* groupOfOurs(QgsLayerTreeGroup* root, const QString& name) {
  QgsLayerTreeGroup* group = root->findGroup(name);
  if (!group) {
    group = root->insertGroup(0, name);
    group->setCustomProperty(kOurGroup, true);
  }
  return group;
}

// The QGIS desktop makes the first layer a run adds current (a hidden level inside our group)
// and adds the next layers beside the current one: the user's own would land in the group.
// They go above it, until the user picks another place in the layer tree.
void keepNewLayersOutOf(QgsLayerTreeGroup* group, QgsProject* project) {
  // Beside the group wherever the user has put it (a folder of their own, say).
  auto* parent = qobject_cast<QgsLayerTreeGroup*>(group->parent());
  const int index = parent ? parent->children().indexOf(group) : -1;
  if (index >= 0 && project->layerTreeRegistryBridge())
    project->layerTreeRegistryBridge()->setLayerInsertionPoint(QgsLayerTreeRegistryBridge::InsertionPoint(parent, index));
}

// Running again with more levels makes a new coarsest level, shown: the levels an earlier run
// showed are hidden, so that one level shows, as after a first run.
void showOnly(QgsLayerTreeLayer* shown, QgsLayerTreeGroup* group) {
  for (QgsLayerTreeNode* child : group->children())
    if (child != shown && child->customProperty(kOrder).isValid()) child->setItemVisibilityChecked(false);
}

}  // namespace

bool loadedByARun(const QgsMapLayer* layer) { return layer && layer->customProperty(kLoaded).toBool(); }

bool reloadedIfLoadedBefore(QgsMapLayer* layer) {
  if (!loadedByARun(layer)) return false;
  layer->reload();
  layer->triggerRepaint();
  return true;
}

void placeLayer(QgsMapLayer* layer, QgsProject* project, const QString& group, int order, bool visible) {
  if (!project) return;
  layer->setCustomProperty(kLoaded, true);
  QgsLayerTreeGroup* root = project->layerTreeRoot();
  QgsLayerTreeLayer* node = root->findLayer(layer);
  if (!node) return;
  auto* parent = qobject_cast<QgsLayerTreeGroup*>(node->parent());
  QgsLayerTreeGroup* target = nullptr;
  if (!group.isEmpty()) target = groupOfOurs(root, group);
  else if (parent && parent != root && parent->customProperty(kOurGroup).toBool()) target = root;
  QgsLayerTreeLayer* placed = node;
  if (target) {
    // Before the first other layer of higher order, counted in the list as it is (QGIS may
    // have put this one in it already). The new node goes in before the old one comes out:
    // a layer left in no node is removed from the project by QGIS.
    const QList<QgsLayerTreeNode*> children = target->children();
    int index = group.isEmpty() ? 0 : children.size();
    for (int i = 0; !group.isEmpty() && i < children.size(); ++i)
      if (children[i] != node && children[i]->customProperty(kOrder).toInt() >= order) {
        index = i;
        break;
      }
    placed = target->insertLayer(index, layer);
    if (parent) parent->removeChildNode(node);
  }
  placed->setCustomProperty(kOrder, order);
  placed->setItemVisibilityChecked(visible);
  if (!group.isEmpty() && visible) showOnly(placed, target);
  if (!group.isEmpty()) keepNewLayersOutOf(target, project);
}

QgsProcessingContext::LayerDetails placedLayerDetails(const QString& name, QgsProject* project, const QString& outputName,
                                                      QgsProcessingLayerPostProcessorInterface* style,
                                                      QgsProcessingUtils::LayerHint hint) {
  QgsProcessingContext::LayerDetails details(name, project, outputName, hint);
  details.forceName = true;  // QGIS would name it after its file or table ("triangles") by default
  details.setPostProcessor(style ? style : new PlacedLayer);
  return details;
}

bool inTemporaryFolder(const QString& path) {
  return QFileInfo(path).absoluteFilePath().startsWith(QFileInfo(QgsProcessingUtils::tempFolder()).absoluteFilePath() +
                                                       QLatin1Char('/'));
}

bool writesForALaterStepOnly(const QVariantMap& parameters, const QgsProcessingContext& context) {
  // A model runs its steps with its own variables (model_path, model_name) in the context;
  // they stay there after it, so the output as given decides.
  if (!context.expressionContext().hasVariable(QStringLiteral("model_path"))) return false;
  const QVariant output = parameters.value(QStringLiteral("OUTPUT"));
  if (output.userType() != QMetaType::QString) return false;
  const QString path = output.toString();
  return path != QgsProcessing::TEMPORARY_OUTPUT && inTemporaryFolder(path);
}

}  // namespace tinlod::qgis
