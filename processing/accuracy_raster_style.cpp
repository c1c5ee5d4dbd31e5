// SPDX-License-Identifier: GPL-3.0-or-later
#include "accuracy_raster_style.h"

#include <qgscolorramp.h>
#include <qgsrasterbandstats.h>
#include <qgsrasterdataprovider.h>
#include <qgsrasterlayer.h>
#include <qgssinglebandpseudocolorrenderer.h>

#include <algorithm>
#include <cmath>

#include "layer_placement.h"
#include "tin_layer_style.h"

namespace tinlod::qgis {

void AccuracyRasterStyle::apply(QgsRasterLayer& layer) {
  QgsRasterDataProvider* provider = layer.dataProvider();
  if (!provider || provider->bandCount() < 1) return;
  // Symmetric about zero, so that white is "no error" whatever the signs' balance; the
  // 2nd and 98th percentiles would hide the very errors the raster is for: the extremes.
  const QgsRasterBandStats stats = provider->bandStatistics(1, QgsRasterBandStats::Min | QgsRasterBandStats::Max);
  double reach = std::max(std::fabs(stats.minimumValue), std::fabs(stats.maximumValue));
  if (!(reach > 0) || !std::isfinite(reach)) reach = 1;
  auto* renderer = new QgsSingleBandPseudoColorRenderer(provider, 1);
  renderer->setClassificationMin(-reach);
  renderer->setClassificationMax(reach);
  renderer->createShader(new QgsColorBrewerColorRamp(QStringLiteral("RdBu"), 11, true));
  layer.setRenderer(renderer);
  layer.triggerRepaint();
}

void AccuracyRasterStyle::postProcessLayer(QgsMapLayer* layer, QgsProcessingContext& context, QgsProcessingFeedback*) {
  if (reloadedIfLoadedBefore(layer)) return;
  if (auto* raster = qobject_cast<QgsRasterLayer*>(layer)) apply(*raster);
  placeLayer(layer, context.project());
}

void AccuracyRasterLoad::remember(QgsProcessingContext& context, const QString& path) {
  path_.clear();
  // A batch row that leaves the raster out has QGIS register "" to load, which it then
  // reports as a layer "not correctly generated", with no name.
  auto layers = context.layersToLoadOnCompletion();
  if (layers.remove(QString())) context.setLayersToLoadOnCompletion(layers);
  if (path.isEmpty() || !context.willLoadLayerOnCompletion(path)) return;
  const QgsProcessingContext::LayerDetails& asked = context.layerToLoadOnCompletionDetails(path);
  // Named after its file, as the TIN layers are: three runs gave three "Accuracy raster".
  path_ = path, name_ = outputBaseName(path, asked.name), outputName_ = asked.outputName, project_ = asked.project;
  reRegister(context);  // styled here too: a run on this thread keeps this list
}

void AccuracyRasterLoad::reRegister(QgsProcessingContext& context) const {
  if (path_.isEmpty()) return;
  context.addLayerToLoadOnCompletion(path_, placedLayerDetails(name_, project_, outputName_, new AccuracyRasterStyle,
                                                               QgsProcessingUtils::LayerHint::Raster));
}

}  // namespace tinlod::qgis
