// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <qgsprocessingcontext.h>

namespace tinlod::qgis {

// Styles a TIN layer that an algorithm loads into the project: triangles as thin outlines
// over a faint fill, vertices as small dots, so that a dense TIN does not come up as a
// solid dark block. Placed in the layer tree by placeLayer (layer_placement.h): a
// hierarchy's levels as one group, in level order.
class TinLayerStyle : public QgsProcessingLayerPostProcessorInterface {
 public:
  // `order` places the layer among the group's layers (QGIS loads results in name order,
  // which would put level_10 before level_2).
  explicit TinLayerStyle(QString group = QString(), bool visible = true, int order = 0)
      : group_(std::move(group)), visible_(visible), order_(order) {}
  void postProcessLayer(QgsMapLayer* layer, QgsProcessingContext& context, QgsProcessingFeedback* feedback) override;

 private:
  QString group_;
  bool visible_;
  int order_;
};

// The name an output's layers are called by: the file's, or `temporaryName` for a
// temporary output (QGIS names its file after the parameter: "OUTPUT").
QString outputBaseName(const QString& path, const QString& temporaryName);

// Asks QGIS to load `layerName` of the GeoPackage when the algorithm finishes, named
// "<baseName> <layer name>" (or just the layer name inside `group`, if given) and styled
// by TinLayerStyle.
void loadTinLayerOnCompletion(QgsProcessingContext& context, const QString& gpkg, const QString& layerName,
                              const QString& outputName, const QString& baseName, const QString& group = QString(),
                              bool visible = true, int order = 0);

// A single TIN's two layers: the triangles, and the vertices hidden (a hundred thousand
// dots would cover the map).
void loadTinOnCompletion(QgsProcessingContext& context, const QString& gpkg, const QString& baseName);

}  // namespace tinlod::qgis
