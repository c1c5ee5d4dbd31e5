// SPDX-License-Identifier: GPL-3.0-or-later
#include "build_hierarchy_algorithm.h"

#include <qgsprocessingoutputs.h>
#include <qgsprocessingparameters.h>
#include <qgsvectorlayer.h>

#include <QFileInfo>
#include <cmath>

#include "group_icon.h"
#include "help_page.h"
#include "layer_placement.h"
#include "parameter_decimals.h"
#include "processing_feedback.h"
#include "source_file.h"
#include "tin_layer_output.h"
#include "tin_layer_style.h"
#include "tinlod/build_job.h"
#include "tinlod/build_summary_text.h"
#include "vertex_index_parameter.h"

namespace tinlod::qgis {
namespace {

const QStringList kMethods{QStringLiteral("degree"), QStringLiteral("volume"), QStringLiteral("normal"),
                           QStringLiteral("error")};

}  // namespace

QString BuildHierarchyAlgorithm::name() const { return QStringLiteral("buildhierarchy"); }
QString BuildHierarchyAlgorithm::displayName() const { return QStringLiteral("Build TIN hierarchy from DEM"); }
QString BuildHierarchyAlgorithm::group() const { return QStringLiteral("TIN construction"); }
QString BuildHierarchyAlgorithm::groupId() const { return QStringLiteral("construction"); }
QStringList BuildHierarchyAlgorithm::tags() const {
  return QStringLiteral("tin,dem,hierarchy,kirkpatrick,simplification,level of detail,lod,delaunay,terrain").split(',');
}

QString BuildHierarchyAlgorithm::shortDescription() const {
  return QStringLiteral("Samples a DEM into a Delaunay TIN and simplifies it level by level into a Kirkpatrick hierarchy of TINs in one GeoPackage.");
}
QIcon BuildHierarchyAlgorithm::icon() const { return groupIcon(groupId()); }
QString BuildHierarchyAlgorithm::helpUrl() const { return helpPageUrl(name()); }

QString BuildHierarchyAlgorithm::shortHelpString() const {
  return QStringLiteral(
             "Samples a DEM into a TIN and simplifies it level by level into a triangulation hierarchy "
             "(Kirkpatrick's, as adapted to terrains by de Berg and Dobrindt), written to one GeoPackage.\n\n"
             "Each level deletes an independent set of the least important vertices (at most Delete "
             "percentage of the current ones, best first) and retriangulates their neighbourhoods so that "
             "the TIN stays Delaunay, until Stop percentage of the original vertices remain.\n\n"
             "Methods: degree (Kirkpatrick: vertices of degree at most Maximum degree, lowest first); "
             "volume (change of the volume under the neighbourhood when the vertex goes, smallest first); "
             "normal (how much the vertex's triangles' normals differ, flattest first); error (largest "
             "vertical distance after deletion to the DEM at every valid cell centre under the neighbourhood; "
             "with Maximum error E a vertex goes only while every such cell stays within max(E, level 0's own "
             "distance there)). Every level's maximum and RMS vertical distance to the DEM at every valid cell "
             "centre it covers is measured, whatever the method. Vertices on the outline of the data and of "
             "nodata holes go while the outline moves less than the Outline tolerance (one DEM cell by "
             "default, growing with the levels as the vertex spacing does), never out over nodata; a raster "
             "edge stays on its line and the raster's corners stay. Points to keep (snapped to the nearest "
             "vertex) and, if asked, peaks and pits (strict local maxima and minima of the DEM in 3 x 3 "
             "cells) are never deleted.\n\n") +
         samplingHelp() +
         QStringLiteral(
             "\n\nOutput: a GeoPackage with layers vertices (with level and fixed), triangles (each "
             "distinct triangle once, with first_level, last_level, group_id, replaced_by and error), "
             "level_0, level_1, ... (one per level, as views), groups (outline of each deleted vertex's "
             "neighbourhood) and levels (counts, times, maximum and RMS error against the DEM, cells covered and "
             "given up, outline vertices per level). The level layers "
             "are loaded as a group, the coarsest visible.\n\n") +
         QStringLiteral("Optional: an accuracy raster of the coarsest level and a report of every level.\n") +
         accuracyHelp();
}

BuildHierarchyAlgorithm* BuildHierarchyAlgorithm::createInstance() const { return new BuildHierarchyAlgorithm(); }

void BuildHierarchyAlgorithm::initAlgorithm(const QVariantMap&) {
  const HierarchyOptions d;
  addDemAndSamplingParameters();
  addParameter(new QgsProcessingParameterEnum(QStringLiteral("METHOD"), QStringLiteral("Importance method"), kMethods,
                                              false, static_cast<int>(d.measure)));
  addParameter(decimals(1, new QgsProcessingParameterNumber(QStringLiteral("DELETE_PCT"), QStringLiteral("Delete percentage per level"),
                                                QgsProcessingParameterNumber::Double, d.deletePct, false, 1, 100)));
  addParameter(decimals(1, new QgsProcessingParameterNumber(QStringLiteral("STOP_PCT"), QStringLiteral("Stop percentage of the original vertices"),
                                                QgsProcessingParameterNumber::Double, d.stopPct, false, 0, 99.9)));
  addParameter(new QgsProcessingParameterFeatureSource(QStringLiteral("FIXED_POINTS"), QStringLiteral("Points to keep"),
                                                       {QgsProcessing::TypeVectorPoint}, QVariant(), true));
  addParameter(new QgsProcessingParameterBoolean(QStringLiteral("FIX_PEAKS_PITS"), QStringLiteral("Keep peaks and pits"), false));
  addParameter(advanced(new QgsProcessingParameterNumber(QStringLiteral("MAX_LEVELS"), QStringLiteral("Maximum levels (0: no limit)"),
                                                         QgsProcessingParameterNumber::Integer, d.maxLevels, false, 0, kMaxLevel)));
  addParameter(advanced(new QgsProcessingParameterNumber(QStringLiteral("MAX_DEGREE"), QStringLiteral("Maximum degree (degree method)"),
                                                         QgsProcessingParameterNumber::Integer, d.maxDegree, false, 3)));
  addParameter(advanced(decimals(2, new QgsProcessingParameterNumber(QStringLiteral("MAX_ERROR"), QStringLiteral("Maximum error, metres (error method)"),
                                                         QgsProcessingParameterNumber::Double, QVariant(), true, 0))));
  addParameter(advanced(decimals(4, new QgsProcessingParameterNumber(QStringLiteral("THRESHOLD"),
                                                         QStringLiteral("Threshold mode: delete every independent vertex below this importance"),
                                                         QgsProcessingParameterNumber::Double, QVariant(), true))));
  addParameter(advanced(decimals(2, new QgsProcessingParameterNumber(QStringLiteral("OUTLINE_TOLERANCE"),
                                                         QStringLiteral("Outline tolerance at level 1, metres (empty: one DEM cell)"),
                                                         QgsProcessingParameterNumber::Double, QVariant(), true, 0))));
  addParameter(advanced(new QgsProcessingParameterBoolean(QStringLiteral("KEEP_OUTLINE"),
                                                          QStringLiteral("Keep every outline vertex (every level covers level 0's area)"), false)));
  addAccuracyParameters(false);
  addParameter(advanced(new QgsProcessingParameterString(QStringLiteral("LEVEL_VIEWS"),
                                                        QStringLiteral("Level views to write (all, or levels such as 0,5,last)"),
                                                        QStringLiteral("all"))));
  addParameter(advanced(new QgsProcessingParameterBoolean(QStringLiteral("GROUP_OUTLINES"),
                                                         QStringLiteral("Write the groups' outline polygons"), true)));
  addParameter(vertexIndexParameter());
  addParameter(new QgsProcessingParameterBoolean(QStringLiteral("LOAD_LEVELS"), QStringLiteral("Open the levels in the map (as a group)"), true));
  addParameter(new QgsProcessingParameterFileDestination(QStringLiteral("OUTPUT"), QStringLiteral("Hierarchy GeoPackage"),
                                                         QStringLiteral("GeoPackage files (*.gpkg *.GPKG)")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("LEVELS"), QStringLiteral("Levels (level 0 included)")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("COARSEST_LEVEL"), QStringLiteral("Number of the coarsest level")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("COARSEST_VERTICES"), QStringLiteral("Vertices of the coarsest level")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("MAX_ERROR"), QStringLiteral("Maximum error of the coarsest level against the DEM (metres)")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("RMSE"), QStringLiteral("RMSE of the coarsest level against the DEM (metres)")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("CELLS_GIVEN_UP"), QStringLiteral("Valid cells the coarsest level's outline gave up")));
  addOutput(trianglesLayerOutput(QStringLiteral("COARSEST_LAYER"), QStringLiteral("Coarsest level layer")));
  addParameterHelp(*this);
}

bool BuildHierarchyAlgorithm::prepareAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                                               QgsProcessingFeedback* feedback) {
  readDemAndSamplingParameters(parameters, context);
  options_ = HierarchyOptions();
  options_.measure = parseMeasure(kMethods.value(parameterAsEnum(parameters, QStringLiteral("METHOD"), context)).toStdString());
  options_.deletePct = parameterAsDouble(parameters, QStringLiteral("DELETE_PCT"), context);
  options_.stopPct = parameterAsDouble(parameters, QStringLiteral("STOP_PCT"), context);
  options_.maxLevels = parameterAsInt(parameters, QStringLiteral("MAX_LEVELS"), context);
  options_.maxDegree = parameterAsInt(parameters, QStringLiteral("MAX_DEGREE"), context);
  if (options_.maxDegree != HierarchyOptions().maxDegree && options_.measure != Measure::Degree)
    throw QgsProcessingException(QStringLiteral("MAX_DEGREE applies to the degree method only: set METHOD to degree or "
                                                "leave MAX_DEGREE at %1").arg(HierarchyOptions().maxDegree));
  const QVariant maxError = parameters.value(QStringLiteral("MAX_ERROR"));
  if (maxError.isValid() && !maxError.toString().isEmpty()) {
    if (options_.measure != Measure::Error)
      throw QgsProcessingException(QStringLiteral("MAX_ERROR applies to the error method only: set METHOD to error or clear MAX_ERROR"));
    options_.maxError = parameterAsDouble(parameters, QStringLiteral("MAX_ERROR"), context);
  }
  const QVariant threshold = parameters.value(QStringLiteral("THRESHOLD"));
  options_.thresholdMode = threshold.isValid() && !threshold.toString().isEmpty();
  if (options_.thresholdMode) options_.threshold = parameterAsDouble(parameters, QStringLiteral("THRESHOLD"), context);
  options_.fixPeaksPits = parameterAsBoolean(parameters, QStringLiteral("FIX_PEAKS_PITS"), context);
  const QVariant tolerance = parameters.value(QStringLiteral("OUTLINE_TOLERANCE"));
  if (tolerance.isValid() && !tolerance.toString().isEmpty())
    options_.outlineTolerance = parameterAsDouble(parameters, QStringLiteral("OUTLINE_TOLERANCE"), context);
  options_.keepOutline = parameterAsBoolean(parameters, QStringLiteral("KEEP_OUTLINE"), context);
  loadLevels_ = parameterAsBoolean(parameters, QStringLiteral("LOAD_LEVELS"), context);
  layers_ = HierarchyLayers();
  const QString views = parameterAsString(parameters, QStringLiteral("LEVEL_VIEWS"), context).trimmed();
  translateErrors([&] { layers_.levelViews = parseLevelList(views.isEmpty() ? "all" : views.toStdString(), "LEVEL_VIEWS"); });
  layers_.groupOutlines = parameterAsBoolean(parameters, QStringLiteral("GROUP_OUTLINES"), context);
  layers_.vertexIndex = parameterAsBoolean(parameters, QStringLiteral("VERTEX_INDEX"), context);
  readAccuracyParameters(parameters, context);
  options_.fixedPoints = sourceFile(parameterDefinition(QStringLiteral("FIXED_POINTS")), parameters, context, feedback,
                                    QStringLiteral("a point layer"));
  translateErrors([&] { options_.validate(); }, parameterNames());
  return true;
}

ParameterNames BuildHierarchyAlgorithm::parameterNames() {
  return samplingParameterNames(ParameterNames{
      {QStringLiteral("-delete_pct"), QStringLiteral("DELETE_PCT")}, {QStringLiteral("-stop_pct"), QStringLiteral("STOP_PCT")},
      {QStringLiteral("-max_levels"), QStringLiteral("MAX_LEVELS")}, {QStringLiteral("-max_degree"), QStringLiteral("MAX_DEGREE")},
      {QStringLiteral("-max_error"), QStringLiteral("MAX_ERROR")},   {QStringLiteral("-threshold"), QStringLiteral("THRESHOLD")},
      {QStringLiteral("-outline_tolerance"), QStringLiteral("OUTLINE_TOLERANCE")},
      {QStringLiteral("-keep_outline"), QStringLiteral("KEEP_OUTLINE")}, {QStringLiteral("-fixed"), QStringLiteral("FIXED_POINTS")},
      {QStringLiteral("-fix_peaks_pits"), QStringLiteral("FIX_PEAKS_PITS")}, {QStringLiteral("-levels"), QStringLiteral("LEVEL_VIEWS")},
      {QStringLiteral("-method"), QStringLiteral("METHOD")}} + accuracyParameterNames());
}

QVariantMap BuildHierarchyAlgorithm::processAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                                                      QgsProcessingFeedback* feedback) {
  const QString output = parameterAsFileOutput(parameters, QStringLiteral("OUTPUT"), context);
  const ParameterNames names = parameterNames();
  const BuildSummary s = translateErrors(
      [&] {
        return runBuildJob(demSource_, output.toStdString(), sample_, options_, true, processingFeedback(feedback, names),
                           accuracy_, layers_);
      },
      names);
  feedback->pushInfo(QStringLiteral("%1 levels (0 to %7): %2 -> %3 vertices (%4 fixed); the coarsest level against the DEM: "
                                    "maximum error %5 m, RMSE %8 m, %9; %6 MB")
                         .arg(s.levels + 1).arg(s.originalVertices).arg(s.coarsestVertices).arg(s.fixedVertices)
                         .arg(s.coarsestError, 0, 'f', 2).arg(s.fileBytes / 1e6, 0, 'f', 1).arg(s.levels)
                         .arg(s.coarsestRmse, 0, 'f', 2).arg(QString::fromStdString(coarsestCellsText(s))));
  if (const std::string cover = levelZeroCoverText(s); !cover.empty()) feedback->pushInfo(QString::fromStdString(cover));
  if (loadLevels_ && !writesForALaterStepOnly(parameters, context)) {
    const QString base = outputBaseName(output, QStringLiteral("TIN hierarchy"));
    for (const std::int32_t level : s.levelViews)
      loadTinLayerOnCompletion(context, output, QStringLiteral("level_%1").arg(level), QStringLiteral("OUTPUT"), base,
                               base + QStringLiteral(" levels"), level == s.levels, level);
  }
  accuracyLoad_.reRegister(context);
  QVariantMap outputs;
  outputs.insert(QStringLiteral("OUTPUT"), output);
  outputs.insert(QStringLiteral("COARSEST_LAYER"), hierarchyLevelLayer(output, s.levels, s.levelViews));
  outputs.insert(QStringLiteral("LEVELS"), s.levels + 1);
  outputs.insert(QStringLiteral("COARSEST_LEVEL"), s.levels);
  outputs.insert(QStringLiteral("COARSEST_VERTICES"), static_cast<qlonglong>(s.coarsestVertices));
  outputs.insert(QStringLiteral("MAX_ERROR"), s.coarsestError);
  outputs.insert(QStringLiteral("RMSE"), s.coarsestRmse);
  outputs.insert(QStringLiteral("CELLS_GIVEN_UP"), static_cast<qlonglong>(s.cellsGivenUp));
  if (!accuracy_.rasterPath.empty()) outputs.insert(QStringLiteral("ACCURACY"), QString::fromStdString(accuracy_.rasterPath));
  if (!accuracy_.reportPath.empty()) outputs.insert(QStringLiteral("REPORT"), QString::fromStdString(accuracy_.reportPath));
  return outputs;
}

}  // namespace tinlod::qgis
