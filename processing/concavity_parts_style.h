// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <qgsprocessingcontext.h>

namespace tinlod::qgis {

// Styles the concavity parts as they load: a colour by class (convex red, straight grey,
// concave blue), the classes in the legend, as the parts mean nothing in one colour.
class ConcavityPartsStyle : public QgsProcessingLayerPostProcessorInterface {
 public:
  void postProcessLayer(QgsMapLayer* layer, QgsProcessingContext& context, QgsProcessingFeedback* feedback) override;
};

}  // namespace tinlod::qgis
