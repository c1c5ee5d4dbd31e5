// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <qgsprocessingalgorithm.h>

#include <optional>
#include <string>

#include "accuracy_raster_style.h"
#include "processing_feedback.h"
#include "tinlod/accuracy_job.h"
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
  // INPUT, BAND and advanced VALID_RANGE; an empty BAND reads as `emptyBand`. Where the
  // heights are checked against a GeoPackage, VALID_RANGE has no default: empty means the
  // range the GeoPackage was made with (validHeights_ is then empty).
  void addDemParameters(bool rangeOfTheGeoPackage = false);
  void readDemParameters(const QVariantMap& parameters, QgsProcessingContext& context, int emptyBand);

  // The accuracy parameters (accuracy_parameters.cpp): REFERENCE, STEP, CONTROL_SPACING,
  // and the ACCURACY raster and REPORT destinations, optional or made by default.
  void addAccuracyParameters(bool createOutputsByDefault);
  // Fills accuracy_ on the main thread, or throws QgsProcessingException naming the parameter.
  void readAccuracyParameters(const QVariantMap& parameters, QgsProcessingContext& context);
  static QString accuracyHelp();
  // The accuracy parameters by the command line's options (-of is ACCURACY's extension).
  static ParameterNames accuracyParameterNames();
  // The help text's paragraphs on sampling, holes and units, shared by the algorithms.
  static QString samplingHelp();
  // VALID_RANGE, or none when it is empty; throws QgsProcessingException for a bad range.
  std::optional<HeightRange> validRange(const QVariantMap& parameters, QgsProcessingContext& context);
  // Flags a parameter Advanced (shown folded in the dialog) and returns it.
  static QgsProcessingParameterDefinition* advanced(QgsProcessingParameterDefinition* parameter);
  // The DEM parameters (BAND, VALID_RANGE) by the command line's options, for the core's
  // messages, and `more` after them; with the sampling parameters too ("consider a smaller
  // -jitter" comes out as JITTER) for the algorithms that sample.
  static ParameterNames demParameterNames(const ParameterNames& more = {});
  static ParameterNames samplingParameterNames(const ParameterNames& more = {});

  std::string demSource_;
  SampleOptions sample_;
  std::optional<HeightRange> validHeights_;
  AccuracyOutputs accuracy_;
  // The accuracy raster's loading into the project, if asked: call reRegister() from
  // processAlgorithm once the raster is written.
  AccuracyRasterLoad accuracyLoad_;
};

}  // namespace tinlod::qgis
