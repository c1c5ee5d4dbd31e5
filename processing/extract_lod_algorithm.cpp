// SPDX-License-Identifier: GPL-3.0-or-later
#include "extract_lod_algorithm.h"

#include <qgscoordinatereferencesystem.h>
#include <qgsprocessingoutputs.h>
#include <qgsprocessingparameters.h>

#include <cmath>
#include <limits>

#include "group_icon.h"
#include "help_page.h"
#include "hierarchy_parameter.h"
#include "layer_placement.h"
#include "parameter_decimals.h"
#include "parameter_given.h"
#include "processing_feedback.h"
#include "source_file.h"
#include "tin_layer_output.h"
#include "tin_layer_style.h"
#include "vertex_index_parameter.h"

namespace tinlod::qgis {
QString ExtractLodAlgorithm::name() const { return QStringLiteral("extractlod"); }
QString ExtractLodAlgorithm::displayName() const { return QStringLiteral("Extract variable level-of-detail TIN"); }
QString ExtractLodAlgorithm::group() const { return QStringLiteral("TIN use"); }
QString ExtractLodAlgorithm::groupId() const { return QStringLiteral("use"); }
QStringList ExtractLodAlgorithm::tags() const {
  return QStringLiteral("tin,lod,level of detail,hierarchy,kirkpatrick,dobrindt,view,terrain,mesh").split(',');
}

QString ExtractLodAlgorithm::shortDescription() const {
  return QStringLiteral("A TIN of varying level of detail from a hierarchy: fine near centres or in a region, coarse far away.");
}
QIcon ExtractLodAlgorithm::icon() const { return groupIcon(groupId()); }
QString ExtractLodAlgorithm::helpUrl() const { return helpPageUrl(name()); }

QString ExtractLodAlgorithm::shortHelpString() const {
  return QStringLiteral(
      "Combines the levels of a TIN hierarchy (from 'Build TIN hierarchy from DEM') into one conforming TIN "
      "that is detailed near the centres of detail, inside a region or where the terrain needs it, and coarse "
      "elsewhere (de Berg and Dobrindt's traversal).\n\n"
      "A deleted vertex is restored when any test given accepts it:\n"
      "- Dropoff (the study's distance test): a vertex deleted at level L comes back when it is closer than "
      "L x dropoff metres to a centre of detail (the centre point, or every point of the centres layer).\n"
      "- Maximum error: while the triangles that replaced it are more than this many metres from the DEM at a "
      "valid cell centre under them (level 0's own triangles are as fine as it gets), plus the error growth (metres per metre) times its distance to the nearest centre.\n"
      "- Region: every vertex whose replacing triangles meet the polygons comes back: full detail there.\n"
      "A vertex that a restored vertex needs comes back as well, so the tests hold everywhere.\n\n"
      "Hierarchy: a GeoPackage of 'Build TIN hierarchy from DEM', or the catalogue GeoPackage of tinlod tiles: "
      "its finished tiles are then one hierarchy and the output one TIN across them, without a crack "
      "(read a tile at a time).\n\n"
      "Output: a GeoPackage TIN ('vertices' and 'triangles' with each triangle's first and last level) in the "
      "hierarchy's CRS.");
}

ExtractLodAlgorithm* ExtractLodAlgorithm::createInstance() const { return new ExtractLodAlgorithm(); }

void ExtractLodAlgorithm::initAlgorithm(const QVariantMap&) {
  addParameter(hierarchyParameter(QStringLiteral("Hierarchy (GeoPackage or one of its layers)")));
  addParameter(new QgsProcessingParameterPoint(QStringLiteral("CENTER"), QStringLiteral("Centre of detail"), QVariant(), true));
  addParameter(new QgsProcessingParameterFeatureSource(QStringLiteral("CENTERS"), QStringLiteral("Centres of detail (point layer)"),
                                                     QList<int>() << QgsProcessing::TypeVectorPoint, QVariant(), true));
  // A distance in the hierarchy's (metric) CRS: the dialog shows its unit from HIERARCHY.
  auto* dropoff = new QgsProcessingParameterDistance(QStringLiteral("DROPOFF"), QStringLiteral("Dropoff distance per level"),
                                                     QVariant(), QStringLiteral("HIERARCHY"), true, 0);
  dropoff->setDefaultUnit(QgsUnitTypes::DistanceMeters);
  addParameter(decimals(1, dropoff));
  addParameter(decimals(2, new QgsProcessingParameterNumber(QStringLiteral("MAX_ERROR"), QStringLiteral("Maximum error (metres)"),
                                                QgsProcessingParameterNumber::Double, QVariant(), true, 0)));
  addParameter(decimals(3, new QgsProcessingParameterNumber(QStringLiteral("ERROR_GROWTH"),
                                                QStringLiteral("Error growth with distance (metres per metre)"),
                                                QgsProcessingParameterNumber::Double, 0, false, 0)));
  addParameter(new QgsProcessingParameterFeatureSource(QStringLiteral("REGION"), QStringLiteral("Region of full detail (polygons)"),
                                                     QList<int>() << QgsProcessing::TypeVectorPolygon, QVariant(), true));
  addParameter(vertexIndexParameter());
  addParameter(new QgsProcessingParameterFileDestination(QStringLiteral("OUTPUT"), QStringLiteral("TIN GeoPackage"),
                                                         QStringLiteral("GeoPackage files (*.gpkg *.GPKG)")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("TRIANGLES"), QStringLiteral("Triangles")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("VERTICES"), QStringLiteral("Vertices")));
  addOutput(trianglesLayerOutput(QStringLiteral("TRIANGLES_LAYER"), QStringLiteral("Triangles layer")));
  addParameterHelp(*this);
}

bool ExtractLodAlgorithm::checkParameterValues(const QVariantMap& parameters, QgsProcessingContext& context, QString* message) const {
  return parametersWithHierarchyAcceptable(*this, parameters, context, message);
}

bool ExtractLodAlgorithm::prepareAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                                           QgsProcessingFeedback* feedback) {
  hierarchy_ = hierarchyFile(parameterDefinition(QStringLiteral("HIERARCHY")), parameters, context);
  options_ = LodJobOptions();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (parameterGiven(parameters, QStringLiteral("CENTER"))) {
    // As picked, in its own CRS (the canvas's, or [EPSG:...] given): the core takes it to
    // the hierarchy's, a catalogue's included.
    const QgsPointXY p = parameterAsPoint(parameters, QStringLiteral("CENTER"), context);
    options_.lod.centres.push_back({p.x(), p.y()});
    const QgsCoordinateReferenceSystem crs = parameterAsPointCrs(parameters, QStringLiteral("CENTER"), context);
    if (crs.isValid()) options_.centresSrs = crs.toWkt(QgsCoordinateReferenceSystem::WKT_PREFERRED_GDAL).toStdString();
  }
  auto fileOf = [&](const QString& name, const QString& kind) {
    return sourceFile(parameterDefinition(name), parameters, context, feedback, kind);
  };
  options_.centresPath = fileOf(QStringLiteral("CENTERS"), QStringLiteral("a point layer"));
  options_.regionPath = fileOf(QStringLiteral("REGION"), QStringLiteral("a polygon layer"));
  options_.lod.dropoff = parameterGiven(parameters, QStringLiteral("DROPOFF")) ? parameterAsDouble(parameters, QStringLiteral("DROPOFF"), context) : nan;
  options_.lod.maxError =
      parameterGiven(parameters, QStringLiteral("MAX_ERROR")) ? parameterAsDouble(parameters, QStringLiteral("MAX_ERROR"), context) : nan;
  options_.lod.errorGrowth = parameterAsDouble(parameters, QStringLiteral("ERROR_GROWTH"), context);
  if (std::isnan(options_.lod.dropoff) && std::isnan(options_.lod.maxError) && options_.regionPath.empty())
    throw QgsProcessingException(QStringLiteral("Give a test: DROPOFF (with CENTER or CENTERS), MAX_ERROR or REGION"));
  if (!std::isnan(options_.lod.dropoff) && options_.lod.centres.empty() && options_.centresPath.empty())
    throw QgsProcessingException(QStringLiteral("DROPOFF needs a centre of detail: set CENTER or CENTERS"));
  return true;
}

QVariantMap ExtractLodAlgorithm::processAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                                                  QgsProcessingFeedback* feedback) {
  const QString output = parameterAsFileOutput(parameters, QStringLiteral("OUTPUT"), context);
  const bool vertexIndex = parameterAsBoolean(parameters, QStringLiteral("VERTEX_INDEX"), context);
  const ParameterNames names{{QStringLiteral("-centers"), QStringLiteral("CENTERS")},
                             {QStringLiteral("-center_srs"), QStringLiteral("the CRS of CENTER")},
                             {QStringLiteral("-center"), QStringLiteral("CENTER")},
                             {QStringLiteral("-dropoff"), QStringLiteral("DROPOFF")},
                             {QStringLiteral("-max_error"), QStringLiteral("MAX_ERROR")},
                             {QStringLiteral("-error_growth"), QStringLiteral("ERROR_GROWTH")},
                             {QStringLiteral("-region"), QStringLiteral("REGION")},
                             {kFileOf + QString::fromStdString(hierarchy_), QStringLiteral("HIERARCHY")}};
  const LodSummary s = translateErrors(
      [&] { return runLodJob(hierarchy_, output.toStdString(), options_, true, processingFeedback(feedback, names), vertexIndex); },
      names);
  feedback->pushInfo(QStringLiteral("%1 triangles (level 0 has %2) and %3 vertices in %4")
                         .arg(s.triangles).arg(s.levelZeroTriangles).arg(s.vertices).arg(QString::fromStdString(s.crsName)));
  if (!writesForALaterStepOnly(parameters, context))
    loadTinLayerOnCompletion(context, output, QStringLiteral("triangles"), QStringLiteral("OUTPUT"),
                             outputBaseName(output, QStringLiteral("level of detail TIN")));
  QVariantMap outputs;
  outputs.insert(QStringLiteral("OUTPUT"), output);
  outputs.insert(QStringLiteral("TRIANGLES_LAYER"), gpkgLayer(output, QStringLiteral("triangles")));
  outputs.insert(QStringLiteral("TRIANGLES"), static_cast<qlonglong>(s.triangles));
  outputs.insert(QStringLiteral("VERTICES"), static_cast<qlonglong>(s.vertices));
  return outputs;
}

}  // namespace tinlod::qgis
