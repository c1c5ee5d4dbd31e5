// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <qgsprocessingcontext.h>
#include <qgsprocessingutils.h>

#include <QString>

class QgsMapLayer;

namespace tinlod::qgis {

// Where an output layer goes in the layer tree once QGIS has loaded it. QGIS adds it beside
// the current layer: after a hierarchy, that is inside its group of levels, where another
// tool's output does not belong.
//
// Without a group, a layer QGIS put in a group of tinlod's goes to the top of the tree.
// With one, it goes into that group (made on first use and marked as tinlod's) at its
// place by `order`: QGIS loads results in name order, which would put level_10 before
// level_2. Either way it is shown or hidden as `visible` says.
void placeLayer(QgsMapLayer* layer, QgsProject* project, const QString& group = QString(), int order = 0,
                bool visible = true);

// A layer an earlier run loaded and styled (QGIS hands a run the layer already on the map
// for the same file, not a new one): true after reloading it, which shows the file the run
// has just written (the layer still reads the file it replaced), keeping the user's style
// and place. Every post-processor starts with it.
bool reloadedIfLoadedBefore(QgsMapLayer* layer);

// Whether a run loaded (placed and styled) the layer, rather than the user.
bool loadedByARun(const QgsMapLayer* layer);

// The details to load an output layer into `project` with: named as given (not after its
// file, as QGIS would by default), placed by placeLayer, or by `style` (which takes over
// placing) if given.
QgsProcessingContext::LayerDetails placedLayerDetails(
    const QString& name, QgsProject* project, const QString& outputName,
    QgsProcessingLayerPostProcessorInterface* style = nullptr,
    QgsProcessingUtils::LayerHint hint = QgsProcessingUtils::LayerHint::Vector);

// Whether `path` is in QGIS's temporary folder for this session (TEMPORARY_OUTPUT's files,
// a model's intermediate ones).
bool inTemporaryFolder(const QString& path);

// Whether an algorithm's OUTPUT (in `parameters`, as given, not resolved) is a file a model's
// step writes only for a later step: its layers are then not loaded, as QGIS loads no
// intermediate layer of a model (such a file, in QGIS's temporary folder, is gone with the
// session). A model hands such a step a path in that folder; a model output comes as the
// user gave it (a path, or TEMPORARY_OUTPUT, loaded as native algorithms' are).
bool writesForALaterStepOnly(const QVariantMap& parameters, const QgsProcessingContext& context);

// placeLayer as a post-processor, for outputs without a style of their own.
class PlacedLayer : public QgsProcessingLayerPostProcessorInterface {
 public:
  void postProcessLayer(QgsMapLayer* layer, QgsProcessingContext& context, QgsProcessingFeedback*) override {
    if (!reloadedIfLoadedBefore(layer)) placeLayer(layer, context.project());
  }
};

}  // namespace tinlod::qgis
