// SPDX-License-Identifier: GPL-3.0-or-later
#include "accuracy_algorithm.h"

#include <qgsprocessingoutputs.h>
#include <qgsprocessingparameters.h>

#include <cmath>

#include "group_icon.h"
#include "help_page.h"
#include "hierarchy_parameter.h"
#include "processing_feedback.h"

namespace tinlod::qgis {
QString AccuracyAlgorithm::name() const { return QStringLiteral("accuracy"); }
QString AccuracyAlgorithm::displayName() const { return QStringLiteral("Accuracy of a TIN hierarchy"); }
QString AccuracyAlgorithm::group() const { return QStringLiteral("TIN accuracy"); }
QString AccuracyAlgorithm::groupId() const { return QStringLiteral("accuracy"); }
QStringList AccuracyAlgorithm::tags() const {
  return QStringLiteral("tin,dem,accuracy,rmse,curvature,b-spline,correlation,error,hierarchy").split(',');
}

QString AccuracyAlgorithm::shortDescription() const {
  return QStringLiteral("Measures every level of a TIN hierarchy against the DEM: RMSE, maximum error, elevation and mean curvature correlations; writes a raster and a report.");
}
QIcon AccuracyAlgorithm::icon() const { return groupIcon(groupId()); }
QString AccuracyAlgorithm::helpUrl() const { return helpPageUrl(name()); }

QString AccuracyAlgorithm::shortHelpString() const {
  return QStringLiteral(
             "Measures how well every level of a TIN hierarchy (or a TIN) written by tinlod represents the "
             "original, and writes an accuracy raster of one level and a report of all levels.\n\n"
             "Hierarchy: a GeoPackage of tinlod, or the catalogue GeoPackage of tinlod tiles (all its finished "
             "tiles measured as one hierarchy, a tile at a time). DEM: the raster the GeoPackage was made from. Band: empty means the band it was sampled from. "
             "Valid heights: cells outside them are nodata; empty means the range the GeoPackage was made with "
             "(-12000 to 9000 m unless widened).\n\n") +
         accuracyHelp() + QStringLiteral("\n\nLevel: the raster's level; -1 (the default) means the coarsest.");
}

AccuracyAlgorithm* AccuracyAlgorithm::createInstance() const { return new AccuracyAlgorithm(); }

void AccuracyAlgorithm::initAlgorithm(const QVariantMap&) {
  addDemParameters(true);
  addParameter(hierarchyParameter(QStringLiteral("Hierarchy or TIN (GeoPackage or one of its layers)")));
  addParameter(new QgsProcessingParameterNumber(QStringLiteral("LEVEL"), QStringLiteral("Level of the raster (-1: the coarsest)"),
                                                QgsProcessingParameterNumber::Integer, -1, false, -1));
  addAccuracyParameters(true);
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("RMSE"), QStringLiteral("RMSE of the raster's level (m)")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("MAX_ERROR"), QStringLiteral("Maximum error of the raster's level (m)")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("R_ELEVATION"), QStringLiteral("Elevation correlation of the raster's level")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("R_MEAN_CURVATURE"),
                                          QStringLiteral("Mean curvature correlation of the raster's level")));
  addParameterHelp(*this);
}

bool AccuracyAlgorithm::checkParameterValues(const QVariantMap& parameters, QgsProcessingContext& context, QString* message) const {
  return parametersWithHierarchyAcceptable(*this, parameters, context, message);
}

bool AccuracyAlgorithm::prepareAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context, QgsProcessingFeedback*) {
  readDemParameters(parameters, context, 0);
  hierarchy_ = hierarchyFile(parameterDefinition(QStringLiteral("HIERARCHY")), parameters, context);
  readAccuracyParameters(parameters, context);
  accuracy_.rasterLevel = parameterAsInt(parameters, QStringLiteral("LEVEL"), context);
  return true;
}

QVariantMap AccuracyAlgorithm::processAlgorithm(const QVariantMap&, QgsProcessingContext& context,
                                               QgsProcessingFeedback* feedback) {
  // The DEM's parameters, not the sampling ones: this algorithm has none.
  const ParameterNames names = demParameterNames(accuracyParameterNames() +
                                                 ParameterNames{{kFileOf + QString::fromStdString(hierarchy_), QStringLiteral("HIERARCHY")},
                                                                {kFileOf + QString::fromStdString(demSource_), QStringLiteral("INPUT")}});
  const AccuracyReport report = translateErrors(
      [&] {
        return runAccuracyJob(demSource_, hierarchy_, accuracy_, sample_.band, sample_.sourceSrs, processingFeedback(feedback, names), validHeights_);
      },
      names);
  const int level = accuracy_.rasterLevel < 0 ? static_cast<int>(report.rows.size()) - 1 : accuracy_.rasterLevel;
  const LevelAccuracy& row = report.rows[static_cast<std::size_t>(level)];
  for (const LevelAccuracy& r : report.rows) {
    QString line = QStringLiteral("level %1: %2 vertices, RMSE %3 m, maximum error %4 m, r elevation %5, r mean curvature %6")
                       .arg(r.level).arg(r.vertices).arg(r.rmse, 0, 'f', 2).arg(r.maxAbsError, 0, 'f', 2)
                       .arg(correlationOf(r, "elevation"), 0, 'f', 6).arg(correlationOf(r, "mean_curvature"), 0, 'f', 4);
    if (std::isfinite(r.insertRmse))
      line += QStringLiteral(", greedy insertion with as many vertices RMSE %1 m (ratio %2)")
                  .arg(r.insertRmse, 0, 'f', 2).arg(r.insertRatio, 0, 'f', 3);
    feedback->pushInfo(line);
  }
  accuracyLoad_.reRegister(context);
  QVariantMap outputs;
  if (!accuracy_.rasterPath.empty()) outputs.insert(QStringLiteral("ACCURACY"), QString::fromStdString(accuracy_.rasterPath));
  if (!accuracy_.reportPath.empty()) outputs.insert(QStringLiteral("REPORT"), QString::fromStdString(accuracy_.reportPath));
  outputs.insert(QStringLiteral("RMSE"), row.rmse);
  outputs.insert(QStringLiteral("MAX_ERROR"), row.maxAbsError);
  outputs.insert(QStringLiteral("R_ELEVATION"), correlationOf(row, "elevation"));
  outputs.insert(QStringLiteral("R_MEAN_CURVATURE"), correlationOf(row, "mean_curvature"));
  return outputs;
}

}  // namespace tinlod::qgis
