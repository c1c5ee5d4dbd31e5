// SPDX-License-Identifier: GPL-3.0-or-later
#include "concavity_algorithm.h"

#include <qgsprocessingoutputs.h>
#include <qgsprocessingparameters.h>
#include <qgsvectorlayer.h>

#include "concavity_parts_style.h"
#include "group_icon.h"
#include "help_page.h"
#include "layer_placement.h"
#include "parameter_decimals.h"
#include "processing_feedback.h"
#include "source_file.h"

namespace tinlod::qgis {

QString ConcavityAlgorithm::name() const { return QStringLiteral("concavity"); }
QString ConcavityAlgorithm::displayName() const { return QStringLiteral("Polyline concavity"); }
QString ConcavityAlgorithm::group() const { return QStringLiteral("Lines"); }
QString ConcavityAlgorithm::groupId() const { return QStringLiteral("lines"); }
QStringList ConcavityAlgorithm::tags() const {
  return QStringLiteral("concavity,convexity,curvature,bend,secant,disk,contour,line").split(',');
}

QString ConcavityAlgorithm::shortDescription() const {
  return QStringLiteral("Secant and disk concavity of each vertex of lines (contours, say): convex, straight or concave parts.");
}
QIcon ConcavityAlgorithm::icon() const { return groupIcon(groupId()); }
QString ConcavityAlgorithm::helpUrl() const { return helpPageUrl(name()); }

QString ConcavityAlgorithm::shortHelpString() const {
  return QStringLiteral(
      "How each vertex of a line layer bends, by two measures, and the lines cut into convex, straight and "
      "concave parts. Positive: the line bulges to its left (convex seen from its left side); reversing a line "
      "flips the signs.\n\n"
      "Secant: the points a window's distance along the line before and after the vertex; the signed area "
      "between the line and their secant over the secant's length squared (undefined within the window of an "
      "end). The window can be a share of each line's length instead (for lines simplified to different "
      "degrees).\n\n"
      "Disk: the share of the disk of the radius (default: the window) around the vertex on the line's left, "
      "minus one half, over one half: from -1 to 1.\n\n"
      "Parts: secant above the threshold convex, below minus the threshold concave, else straight.\n\n"
      "Output: layers 'vertices' (line, vertex, secant, disk) and 'parts' (feature, class). A layer in degrees "
      "is measured in the UTM zone of its centre.");
}

ConcavityAlgorithm* ConcavityAlgorithm::createInstance() const { return new ConcavityAlgorithm(); }

void ConcavityAlgorithm::initAlgorithm(const QVariantMap&) {
  addParameter(new QgsProcessingParameterFeatureSource(QStringLiteral("INPUT"), QStringLiteral("Lines"),
                                                     QList<int>() << QgsProcessing::TypeVectorLine));
  addParameter(decimals(1, new QgsProcessingParameterNumber(QStringLiteral("WINDOW"), QStringLiteral("Window along the line (metres)"),
                                                QgsProcessingParameterNumber::Double, 100, false, 0)));
  auto* fraction = decimals(2, new QgsProcessingParameterNumber(QStringLiteral("WINDOW_FRACTION"),
                                                    QStringLiteral("Window as a share of each line's length (0: use WINDOW)"),
                                                    QgsProcessingParameterNumber::Double, 0, false, 0, 0.49));
  fraction->setFlags(fraction->flags() | QgsProcessingParameterDefinition::FlagAdvanced);
  addParameter(fraction);
  addParameter(decimals(1, new QgsProcessingParameterNumber(QStringLiteral("RADIUS"), QStringLiteral("Disk radius (metres; 0: the window)"),
                                                QgsProcessingParameterNumber::Double, 0, false, 0)));
  addParameter(decimals(3, new QgsProcessingParameterNumber(QStringLiteral("THRESHOLD"), QStringLiteral("Secant threshold for the parts"),
                                                QgsProcessingParameterNumber::Double, ConcavityOptions().threshold, false, 0)));
  addParameter(new QgsProcessingParameterFileDestination(QStringLiteral("OUTPUT"), QStringLiteral("Concavity"),
                                                         QStringLiteral("GeoPackage files (*.gpkg *.GPKG)")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("VERTICES"), QStringLiteral("Vertices")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("CONVEX"), QStringLiteral("Convex parts")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("STRAIGHT"), QStringLiteral("Straight parts")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("CONCAVE"), QStringLiteral("Concave parts")));
  addParameterHelp(*this);
}

bool ConcavityAlgorithm::prepareAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                                           QgsProcessingFeedback* feedback) {
  lines_ = sourceFile(parameterDefinition(QStringLiteral("INPUT")), parameters, context, feedback, QStringLiteral("a line layer"));
  options_ = ConcavityOptions();
  options_.windowFraction = parameterAsDouble(parameters, QStringLiteral("WINDOW_FRACTION"), context);
  options_.window = options_.windowFraction > 0 ? 0 : parameterAsDouble(parameters, QStringLiteral("WINDOW"), context);
  options_.radius = parameterAsDouble(parameters, QStringLiteral("RADIUS"), context);
  options_.threshold = parameterAsDouble(parameters, QStringLiteral("THRESHOLD"), context);
  if (!(options_.window > 0) && !(options_.windowFraction > 0))
    throw QgsProcessingException(QStringLiteral("WINDOW must be more than 0 metres (or set WINDOW_FRACTION)"));
  return true;
}

QVariantMap ConcavityAlgorithm::processAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                                                 QgsProcessingFeedback* feedback) {
  const QString output = parameterAsFileOutput(parameters, QStringLiteral("OUTPUT"), context);
  const ParameterNames names{{QStringLiteral("LINES"), QStringLiteral("INPUT")}, {QStringLiteral("-window"), QStringLiteral("WINDOW")},
                             {QStringLiteral("-radius"), QStringLiteral("RADIUS")}, {QStringLiteral("-threshold"), QStringLiteral("THRESHOLD")}};
  const ConcavitySummary s =
      translateErrors([&] { return runConcavityJob(lines_, output.toStdString(), options_, true, processingFeedback(feedback, names)); },
                      names);
  feedback->pushInfo(QStringLiteral("%1 vertices of %2 lines; parts: %3 convex, %4 straight, %5 concave")
                         .arg(s.vertices).arg(s.lines).arg(s.convex).arg(s.straight).arg(s.concave));
  if (!writesForALaterStepOnly(parameters, context))
    context.addLayerToLoadOnCompletion(output + QStringLiteral("|layername=parts"),
                                       placedLayerDetails(QStringLiteral("concavity parts"), context.project(),
                                                          QStringLiteral("OUTPUT"), new ConcavityPartsStyle));
  QVariantMap outputs;
  outputs.insert(QStringLiteral("OUTPUT"), output);
  outputs.insert(QStringLiteral("VERTICES"), static_cast<qlonglong>(s.vertices));
  outputs.insert(QStringLiteral("CONVEX"), static_cast<qlonglong>(s.convex));
  outputs.insert(QStringLiteral("STRAIGHT"), static_cast<qlonglong>(s.straight));
  outputs.insert(QStringLiteral("CONCAVE"), static_cast<qlonglong>(s.concave));
  return outputs;
}

}  // namespace tinlod::qgis
