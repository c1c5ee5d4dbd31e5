// SPDX-License-Identifier: GPL-3.0-or-later
// The accuracy parameters of DemAlgorithm, shared by tinlod:accuracy and tinlod:buildhierarchy.
#include <qgsprocessingparameters.h>

#include <QFileInfo>

#include "dem_algorithm.h"
#include "processing_feedback.h"
#include "tinlod/accuracy_raster.h"

namespace tinlod::qgis {
namespace {

const QStringList kReferences{QStringLiteral("Original TIN (level 0, as in the study)"), QStringLiteral("DEM")};

// A path QGIS did not fill in (an optional output left empty) reads as empty.
QString optionalPath(const QString& path) {
  return path.isEmpty() || path == QLatin1String("memory:") ? QString() : path;
}

}  // namespace

void DemAlgorithm::addAccuracyParameters(bool createOutputsByDefault) {
  const AccuracyOptions d;
  addParameter(advanced(new QgsProcessingParameterEnum(QStringLiteral("REFERENCE"), QStringLiteral("Accuracy reference"),
                                                       kReferences, false, 0)));
  addParameter(advanced(new QgsProcessingParameterNumber(QStringLiteral("STEP"), QStringLiteral("Test points every n-th DEM cell"),
                                                         QgsProcessingParameterNumber::Integer, d.step, false, 1, 1000)));
  addParameter(advanced(new QgsProcessingParameterNumber(QStringLiteral("CONTROL_SPACING"),
                                                         QStringLiteral("B-spline control points every n test points"),
                                                         QgsProcessingParameterNumber::Integer, d.controlSpacing, false, 1, 1000)));
  addParameter(advanced(new QgsProcessingParameterBoolean(
      QStringLiteral("COMPARE_INSERT"), QStringLiteral("Compare each level with greedy insertion at its size"), false)));
  addParameter(new QgsProcessingParameterRasterDestination(QStringLiteral("ACCURACY"), QStringLiteral("Accuracy raster"),
                                                           QVariant(), true, createOutputsByDefault));
  addParameter(new QgsProcessingParameterFileDestination(
      QStringLiteral("REPORT"), QStringLiteral("Accuracy report"),
      QStringLiteral("HTML files (*.html);;CSV files (*.csv);;JSON files (*.json)"), QVariant(), true, createOutputsByDefault));
}

void DemAlgorithm::readAccuracyParameters(const QVariantMap& parameters, QgsProcessingContext& context) {
  accuracy_ = AccuracyOutputs();
  accuracy_.overwrite = true;  // QGIS has asked before replacing a destination; inputs stay refused
  accuracy_.options.reference = parameterAsEnum(parameters, QStringLiteral("REFERENCE"), context) == 0 ? Reference::Tin : Reference::Dem;
  accuracy_.options.step = parameterAsInt(parameters, QStringLiteral("STEP"), context);
  accuracy_.options.controlSpacing = parameterAsInt(parameters, QStringLiteral("CONTROL_SPACING"), context);
  accuracy_.compareInsert = parameterAsBoolean(parameters, QStringLiteral("COMPARE_INSERT"), context);
  const QString raster = optionalPath(parameterAsOutputLayer(parameters, QStringLiteral("ACCURACY"), context));
  accuracy_.rasterPath = raster.toStdString();
  accuracyLoad_.remember(context, raster);
  if (!raster.isEmpty()) {
    accuracy_.raster.format = rasterFormatFor(accuracy_.rasterPath);
    // A name GDAL knows no format for was written as a GeoTIFF under that name.
    if (accuracy_.raster.format.empty())
      throw QgsProcessingException(QStringLiteral("ACCURACY: no GDAL raster format is named by the extension '.%1' of '%2': "
                                                  "name the file .tif")
                                       .arg(QFileInfo(raster).suffix(), raster));
  }
  accuracy_.reportPath = optionalPath(parameterAsFileOutput(parameters, QStringLiteral("REPORT"), context)).toStdString();
  translateErrors([&] { accuracy_.validate(); }, accuracyParameterNames());
}

ParameterNames DemAlgorithm::accuracyParameterNames() {
  return {{QStringLiteral("-level"), QStringLiteral("LEVEL")},
          {QStringLiteral("-accuracy"), QStringLiteral("ACCURACY")},
          {QStringLiteral("-of"), QStringLiteral("ACCURACY")},
          {QStringLiteral("-report"), QStringLiteral("REPORT")},
          {QStringLiteral("-step"), QStringLiteral("STEP")},
          {QStringLiteral("-reference"), QStringLiteral("REFERENCE")},
          {QStringLiteral("-control"), QStringLiteral("CONTROL_SPACING")}};
}

QString DemAlgorithm::accuracyHelp() {
  return QStringLiteral(
      "Accuracy: each level is interpolated linearly at test points (the centre of every n-th DEM cell), "
      "and compared with the reference: the original TIN (level 0, as in the study) or the DEM itself. "
      "Elevation: RMSE, mean error, maximum error and its place, Moran's I of the error. A uniform cubic "
      "B-spline surface is fitted to each interpolated grid (control points every CONTROL_SPACING test "
      "points: fewer follow the triangles' facets, more smooth over them), and the correlation r, means "
      "and standard deviations of elevation, slope, aspect, mean, Gaussian, profile and plan curvature "
      "are compared.\n\n"
      "Accuracy raster (this, the report or both): on the DEM's grid and CRS (every STEP-th cell), band 1 "
      "elevation difference (simplified - reference, "
      "m), band 2 mean curvature difference, bands 3 and 4 the reference's and the simplified TIN's mean "
      "curvature (1/m; positive in hollows). Report: every level, as HTML with plots, CSV or JSON, "
      "following the file's extension.\n\n"
      "Compare with greedy insertion (advanced, off by default): greedy insertion (Garland and Heckbert) over "
      "the same sampled points is run to exactly each level's number of vertices and measured the same way; the "
      "report gains its RMSE and the ratio level RMSE / insert RMSE (1: as good as greedy insertion with as "
      "many vertices, 2: twice its error). It adds about one insertion and one measurement per level.");
}

}  // namespace tinlod::qgis
