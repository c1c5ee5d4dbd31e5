// SPDX-License-Identifier: GPL-3.0-or-later
#include "locate_algorithm.h"

#include <qgsprocessingoutputs.h>
#include <qgsprocessingparameters.h>
#include <qgsvectorlayer.h>

#include "group_icon.h"
#include "help_page.h"
#include "hierarchy_parameter.h"
#include "layer_placement.h"
#include "processing_feedback.h"
#include "source_file.h"
#include "tin_layer_style.h"
#include "tinlod/locate_job.h"

namespace tinlod::qgis {

QString LocateAlgorithm::name() const { return QStringLiteral("locate"); }
QString LocateAlgorithm::displayName() const { return QStringLiteral("TIN elevation at points"); }
QString LocateAlgorithm::group() const { return QStringLiteral("TIN use"); }
QString LocateAlgorithm::groupId() const { return QStringLiteral("use"); }
QStringList LocateAlgorithm::tags() const {
  return QStringLiteral("tin,elevation,height,point location,kirkpatrick,hierarchy,interpolate,drape").split(',');
}

QString LocateAlgorithm::shortDescription() const {
  return QStringLiteral("Elevation of points on a level of a TIN hierarchy, each point located through the hierarchy.");
}
QIcon LocateAlgorithm::icon() const { return groupIcon(groupId()); }
QString LocateAlgorithm::helpUrl() const { return helpPageUrl(name()); }

QString LocateAlgorithm::shortHelpString() const {
  return QStringLiteral(
      "Adds the elevation of a TIN at every point of a point layer. Each point is located through the "
      "hierarchy (Kirkpatrick's search: the coarsest level, then the triangles each one replaced, down to the "
      "level asked for) and the height of the containing triangle is interpolated linearly.\n\n"
      "Hierarchy: a GeoPackage of 'Build TIN hierarchy from DEM' (or a TIN of the other tinlod algorithms), "
      "or the catalogue GeoPackage of tinlod tiles. "
      "Level: 0, the default, is the original TIN.\n\n"
      "Output: layer 'points' of a GeoPackage: every point with its attributes, in its own CRS, plus "
      "'elevation' and 'triangle' (the id in the hierarchy's 'triangles' layer); both are null for a point "
      "outside the TIN or in a hole (one beyond the raster's edge by at most 5 % of a DEM cell, as the edge "
      "cells' centres of a DEM in degrees are, takes the nearest triangle's plane; not one beside a hole). From a catalogue, also 'tile' (the tile as column,row, whose "
      "'triangles' layer the id is in).");
}

LocateAlgorithm* LocateAlgorithm::createInstance() const { return new LocateAlgorithm(); }

void LocateAlgorithm::initAlgorithm(const QVariantMap&) {
  addParameter(new QgsProcessingParameterFeatureSource(QStringLiteral("INPUT"), QStringLiteral("Points"),
                                                     QList<int>() << QgsProcessing::TypeVectorPoint));
  addParameter(hierarchyParameter(QStringLiteral("Hierarchy (GeoPackage or one of its layers)")));
  addParameter(new QgsProcessingParameterNumber(QStringLiteral("LEVEL"), QStringLiteral("Level (0: the original TIN, -1: the coarsest)"),
                                                QgsProcessingParameterNumber::Integer, 0, false, -1));
  addParameter(new QgsProcessingParameterFileDestination(QStringLiteral("OUTPUT"), QStringLiteral("Points with elevation"),
                                                         QStringLiteral("GeoPackage files (*.gpkg *.GPKG)")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("POINTS"), QStringLiteral("Points")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("LOCATED"), QStringLiteral("Points on the TIN")));
  addParameterHelp(*this);
}

bool LocateAlgorithm::checkParameterValues(const QVariantMap& parameters, QgsProcessingContext& context, QString* message) const {
  return parametersWithHierarchyAcceptable(*this, parameters, context, message);
}

bool LocateAlgorithm::prepareAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                                       QgsProcessingFeedback* feedback) {
  points_ = sourceFile(parameterDefinition(QStringLiteral("INPUT")), parameters, context, feedback, QStringLiteral("a point layer"));
  hierarchy_ = hierarchyFile(parameterDefinition(QStringLiteral("HIERARCHY")), parameters, context);
  level_ = parameterAsInt(parameters, QStringLiteral("LEVEL"), context);
  return true;
}

QVariantMap LocateAlgorithm::processAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                                              QgsProcessingFeedback* feedback) {
  const QString output = parameterAsFileOutput(parameters, QStringLiteral("OUTPUT"), context);
  const LocateSummary s = translateErrors(
      [&] { return runLocateJob(hierarchy_, points_, output.toStdString(), level_, true, processingFeedback(feedback)); },
      {{QStringLiteral("-level"), QStringLiteral("LEVEL")},
       {QStringLiteral("points:"), QStringLiteral("INPUT")},
       {kFileOf + QString::fromStdString(hierarchy_), QStringLiteral("HIERARCHY")}});
  feedback->pushInfo(QStringLiteral("%1 of %2 points on the %3TIN of level %4")
                         .arg(s.located)
                         .arg(s.points)
                         .arg(s.unfinishedTiles.empty() ? QString() : QStringLiteral("finished tiles' "))
                         .arg(s.level));
  // As small dots: thousands of QGIS's default markers would hide the map. Named after the
  // file, as the TIN layers are: a batch's outputs were all "points with elevation".
  if (!writesForALaterStepOnly(parameters, context)) {
    const QString base = outputBaseName(output, QString());
    const QString name = base.isEmpty() ? QStringLiteral("points with elevation") : base + QStringLiteral(" points");
    context.addLayerToLoadOnCompletion(output + QStringLiteral("|layername=points"),
                                       placedLayerDetails(name, context.project(), QStringLiteral("OUTPUT"), new TinLayerStyle));
  }
  QVariantMap outputs;
  outputs.insert(QStringLiteral("OUTPUT"), output);
  outputs.insert(QStringLiteral("POINTS"), static_cast<qlonglong>(s.points));
  outputs.insert(QStringLiteral("LOCATED"), static_cast<qlonglong>(s.located));
  return outputs;
}

}  // namespace tinlod::qgis
