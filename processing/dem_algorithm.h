// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <qgsprocessingalgorithm.h>

#include <string>

#include "tinlod/sample_options.h"

namespace tinlod::qgis {

// What every algorithm that starts from a DEM shares: the INPUT and BAND parameters, the
// sampling parameters (BLOCK, and advanced JITTER, SEED, TARGET_CRS), and reading them on
// the main thread, where QGIS layers may be touched.
class DemAlgorithm : public QgsProcessingAlgorithm {
 protected:
  void addDemAndSamplingParameters();
  // Call from prepareAlgorithm: fills demSource_ and sample_, or throws
  // QgsProcessingException naming the parameter.
  void readDemAndSamplingParameters(const QVariantMap& parameters, QgsProcessingContext& context);
  // The help text's paragraphs on sampling, holes and units, shared by the algorithms.
  static QString samplingHelp();
  // Flags a parameter Advanced (shown folded in the dialog) and returns it.
  static QgsProcessingParameterDefinition* advanced(QgsProcessingParameterDefinition* parameter);

  std::string demSource_;
  SampleOptions sample_;
};

}  // namespace tinlod::qgis
