// SPDX-License-Identifier: GPL-3.0-or-later
#include "dp_values_algorithm.h"

#include <qgsprocessingoutputs.h>
#include <qgsprocessingparameters.h>
#include <qgsvectorlayer.h>

#include "group_icon.h"
#include "help_page.h"
#include "layer_placement.h"
#include "parameter_decimals.h"
#include "processing_feedback.h"
#include "source_file.h"

namespace tinlod::qgis {

namespace {

// The lines with their values, and the other layers asked for: a threshold's simplified
// lines, the vertex points.
void loadDpLayers(const QString& output, const DpOptions& options, QgsProcessingContext& context) {
  context.addLayerToLoadOnCompletion(output + QStringLiteral("|layername=lines"),
                                     placedLayerDetails(QStringLiteral("lines with DP values"), context.project(),
                                                        QStringLiteral("OUTPUT")));
  if (options.threshold >= 0)
    context.addLayerToLoadOnCompletion(output + QStringLiteral("|layername=simplified"),
                                       placedLayerDetails(QStringLiteral("lines simplified at %1 m").arg(options.threshold),
                                                          context.project(), QStringLiteral("OUTPUT")));
  if (options.points)
    context.addLayerToLoadOnCompletion(output + QStringLiteral("|layername=vertices"),
                                       placedLayerDetails(QStringLiteral("vertices with DP values"), context.project(),
                                                          QStringLiteral("OUTPUT")));
}

}  // namespace

QString DpValuesAlgorithm::name() const { return QStringLiteral("dpvalues"); }
QString DpValuesAlgorithm::displayName() const { return QStringLiteral("Douglas-Peucker simplification values"); }
QString DpValuesAlgorithm::group() const { return QStringLiteral("Lines"); }
QString DpValuesAlgorithm::groupId() const { return QStringLiteral("lines"); }
QStringList DpValuesAlgorithm::tags() const {
  return QStringLiteral("douglas,peucker,ramer,simplify,generalize,contour,line,tolerance").split(',');
}

QString DpValuesAlgorithm::shortDescription() const {
  return QStringLiteral("Douglas-Peucker value of each vertex of lines: the tolerance at which it would be dropped.");
}
QIcon DpValuesAlgorithm::icon() const { return groupIcon(groupId()); }
QString DpValuesAlgorithm::helpUrl() const { return helpPageUrl(name()); }

QString DpValuesAlgorithm::shortHelpString() const {
  return QStringLiteral(
      "Computes the Douglas-Peucker simplification value of every vertex of a line layer once, so that any "
      "threshold can be applied later: a line simplified at threshold t keeps the vertices whose value exceeds t "
      "(the classic Douglas-Peucker simplification with tolerance t).\n\n"
      "Output: layer 'lines' (LineStringM: M is each vertex's value in metres; endpoints, kept at every "
      "threshold, have M = 1e300) with the source feature id; optionally layer 'vertices' (points with line, "
      "vertex and value). With a threshold, also layer 'simplified' and the number of crossings between "
      "simplified lines (contours that simplification makes cross). A layer in degrees is measured in the UTM "
      "zone of its centre.");
}

DpValuesAlgorithm* DpValuesAlgorithm::createInstance() const { return new DpValuesAlgorithm(); }

void DpValuesAlgorithm::initAlgorithm(const QVariantMap&) {
  addParameter(new QgsProcessingParameterFeatureSource(QStringLiteral("INPUT"), QStringLiteral("Lines"),
                                                     QList<int>() << QgsProcessing::TypeVectorLine));
  addParameter(decimals(2, new QgsProcessingParameterNumber(QStringLiteral("THRESHOLD"),
                                                QStringLiteral("Threshold for the simplified lines and crossings (metres)"),
                                                QgsProcessingParameterNumber::Double, QVariant(), true, 0)));
  addParameter(new QgsProcessingParameterBoolean(QStringLiteral("POINTS"), QStringLiteral("Also write a vertex layer"), false));
  addParameter(new QgsProcessingParameterFileDestination(QStringLiteral("OUTPUT"), QStringLiteral("Lines with values"),
                                                         QStringLiteral("GeoPackage files (*.gpkg *.GPKG)")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("LINES"), QStringLiteral("Lines")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("VERTICES"), QStringLiteral("Vertices")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("CROSSINGS"), QStringLiteral("Crossings at the threshold")));
  addParameterHelp(*this);
}

bool DpValuesAlgorithm::prepareAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                                          QgsProcessingFeedback* feedback) {
  lines_ = sourceFile(parameterDefinition(QStringLiteral("INPUT")), parameters, context, feedback, QStringLiteral("a line layer"));
  options_ = DpOptions();
  const QVariant threshold = parameters.value(QStringLiteral("THRESHOLD"));
  if (threshold.isValid() && !threshold.toString().isEmpty())
    options_.threshold = parameterAsDouble(parameters, QStringLiteral("THRESHOLD"), context);
  options_.points = parameterAsBool(parameters, QStringLiteral("POINTS"), context);
  return true;
}

QVariantMap DpValuesAlgorithm::processAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                                                QgsProcessingFeedback* feedback) {
  const QString output = parameterAsFileOutput(parameters, QStringLiteral("OUTPUT"), context);
  const ParameterNames names{{QStringLiteral("LINES"), QStringLiteral("INPUT")}, {QStringLiteral("-threshold"), QStringLiteral("THRESHOLD")}};
  const DpSummary s = translateErrors(
      [&] { return runDpJob(lines_, output.toStdString(), options_, true, processingFeedback(feedback, names)); }, names);
  feedback->pushInfo(QStringLiteral("%1 vertices of %2 lines in %3").arg(s.vertices).arg(s.lines).arg(QString::fromStdString(s.crsName)));
  if (options_.threshold >= 0)
    feedback->pushInfo(QStringLiteral("At threshold %1 m: %2 vertices kept, %3 crossings between simplified lines")
                           .arg(options_.threshold).arg(s.keptVertices).arg(s.crossings));
  if (!writesForALaterStepOnly(parameters, context)) loadDpLayers(output, options_, context);
  QVariantMap outputs;
  outputs.insert(QStringLiteral("OUTPUT"), output);
  outputs.insert(QStringLiteral("LINES"), static_cast<qlonglong>(s.lines));
  outputs.insert(QStringLiteral("VERTICES"), static_cast<qlonglong>(s.vertices));
  outputs.insert(QStringLiteral("CROSSINGS"), static_cast<qlonglong>(s.crossings));
  return outputs;
}

}  // namespace tinlod::qgis
