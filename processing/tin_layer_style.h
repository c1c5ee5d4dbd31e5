// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <qgsprocessingcontext.h>

namespace tinlod::qgis {

// Styles a TIN layer that an algorithm loads into the project: triangles as thin outlines
// over a faint fill, vertices as small dots, so that a dense TIN does not come up as a
// solid dark block.
class TinLayerStyle : public QgsProcessingLayerPostProcessorInterface {
 public:
  void postProcessLayer(QgsMapLayer* layer, QgsProcessingContext& context, QgsProcessingFeedback* feedback) override;
};

// Asks QGIS to load `layerName` of the GeoPackage when the algorithm finishes, named
// "<file name> <layer name>" and styled by TinLayerStyle.
void loadTinLayerOnCompletion(QgsProcessingContext& context, const QString& gpkg, const QString& layerName,
                              const QString& outputName);

}  // namespace tinlod::qgis
