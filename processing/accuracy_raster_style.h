// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <qgsprocessingcontext.h>

class QgsRasterLayer;

namespace tinlod::qgis {

// Styles the accuracy raster as it loads: band 1 (elevation difference, TIN minus
// reference) on a diverging ramp centred on zero, blue where the TIN is too low and red
// where it is too high. QGIS would otherwise show the first three of its four bands as an
// RGB composite, which means nothing; the others keep their names, a click away in the
// layer's properties.
class AccuracyRasterStyle : public QgsProcessingLayerPostProcessorInterface {
 public:
  void postProcessLayer(QgsMapLayer* layer, QgsProcessingContext& context, QgsProcessingFeedback* feedback) override;
  // The style alone, for a layer already loaded.
  static void apply(QgsRasterLayer& layer);
};

// Where the user asked for the accuracy raster to be opened (the dialog's "Open output
// file", runAndLoadResults), QGIS registers it while the parameters are read on the main
// thread; a background run's context then replaces that list. remember() takes the request
// there; reRegister() gives it back, styled, to the context the algorithm runs in.
class AccuracyRasterLoad {
 public:
  void remember(QgsProcessingContext& context, const QString& path);
  void reRegister(QgsProcessingContext& context) const;

 private:
  QString path_;
  QString name_;
  QString outputName_;
  QgsProject* project_ = nullptr;
};

}  // namespace tinlod::qgis
