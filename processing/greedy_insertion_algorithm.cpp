// SPDX-License-Identifier: GPL-3.0-or-later
#include "greedy_insertion_algorithm.h"

#include <qgsprocessingoutputs.h>
#include <qgsprocessingparameters.h>

#include "group_icon.h"
#include "help_page.h"
#include "layer_placement.h"
#include "parameter_decimals.h"
#include "processing_feedback.h"
#include "tin_layer_output.h"
#include "tin_layer_style.h"
#include "tinlod/insert_job.h"
#include "vertex_index_parameter.h"

namespace tinlod::qgis {
namespace {

const QStringList kDelaunay{QStringLiteral("On the ground, in metres"), QStringLiteral("On the DEM's grid, square cells")};
const QStringList kCandidates{QStringLiteral("Every valid DEM cell"), QStringLiteral("The vertices of the sampled TIN")};

}  // namespace

QString GreedyInsertionAlgorithm::name() const { return QStringLiteral("greedyinsertion"); }
QString GreedyInsertionAlgorithm::displayName() const { return QStringLiteral("Greedy insertion TIN"); }
QString GreedyInsertionAlgorithm::group() const { return QStringLiteral("TIN construction"); }
QString GreedyInsertionAlgorithm::groupId() const { return QStringLiteral("construction"); }
QStringList GreedyInsertionAlgorithm::tags() const {
  return QStringLiteral("tin,dem,delaunay,greedy,insertion,garland,heckbert,tolerance,simplify,terrain,mesh").split(',');
}

QString GreedyInsertionAlgorithm::shortDescription() const {
  return QStringLiteral("A TIN from a DEM by greedy insertion (Garland and Heckbert) until every cell is within a vertical tolerance.");
}
QIcon GreedyInsertionAlgorithm::icon() const { return groupIcon(groupId()); }
QString GreedyInsertionAlgorithm::helpUrl() const { return helpPageUrl(name()); }

QString GreedyInsertionAlgorithm::shortHelpString() const {
  return QStringLiteral(
             "Greedy insertion (Garland and Heckbert): a Delaunay TIN from a DEM made by inserting, again and "
             "again, the point of largest vertical error, until every point is within the maximum error or a "
             "vertex or triangle count is reached (whichever comes first).\n\n"
             "Maximum error: metres. Empty means 1 m, or no error limit when a vertex or triangle count is "
             "given; 0 inserts until the TIN is exact. The error is measured again at every valid cell after "
             "the run (outputs MAX_ERROR and RMSE).\n\n"
             "Candidates: every valid DEM cell (DEM to TIN; the last row and column included), or only the "
             "vertices of the TIN 'Sample TIN from DEM' makes with the same block, jitter and seed (the "
             "study's comparison with the delete methods on the same input). The run starts from the convex "
             "hull of the valid cells (the corners of a full raster) at their own heights. No triangle spans "
             "a nodata hole.\n\n"
             "Delaunay criterion (advanced): on the ground in metres (default), or on the DEM's grid with "
             "square cells as delatin and most tools do; they differ only where cells are not square on the "
             "ground (a geographic DEM away from the equator).\n\n"
             "Output: a GeoPackage with the layers of 'Sample TIN from DEM'; each vertex also has 'insertion', "
             "its place in the insertion order, and 'error_before': the vertices with insertion at most k form a "
             "coarser TIN (a progressive TIN) whose maximum error is the error_before of the next vertex.\n\n") +
         samplingHelp();
}

GreedyInsertionAlgorithm* GreedyInsertionAlgorithm::createInstance() const { return new GreedyInsertionAlgorithm(); }

void GreedyInsertionAlgorithm::initAlgorithm(const QVariantMap&) {
  addDemAndSamplingParameters();
  addParameter(decimals(2, new QgsProcessingParameterNumber(QStringLiteral("MAX_ERROR"),
                                                QStringLiteral("Maximum vertical error, metres (empty: 1, or none when a count is set)"),
                                                QgsProcessingParameterNumber::Double, QVariant(), true, 0)));
  addParameter(new QgsProcessingParameterNumber(QStringLiteral("MAX_VERTICES"), QStringLiteral("Maximum vertices (0: no limit)"),
                                                QgsProcessingParameterNumber::Integer, 0, false, 0));
  addParameter(advanced(new QgsProcessingParameterNumber(QStringLiteral("MAX_TRIANGLES"),
                                                         QStringLiteral("Maximum triangles (0: no limit)"),
                                                         QgsProcessingParameterNumber::Integer, 0, false, 0)));
  addParameter(new QgsProcessingParameterEnum(QStringLiteral("CANDIDATES"), QStringLiteral("Candidates"), kCandidates, false, 0));
  addParameter(advanced(new QgsProcessingParameterEnum(QStringLiteral("DELAUNAY"), QStringLiteral("Delaunay criterion"),
                                                       kDelaunay, false, 0)));
  addParameter(vertexIndexParameter());
  addParameter(new QgsProcessingParameterFileDestination(QStringLiteral("OUTPUT"), QStringLiteral("TIN GeoPackage"),
                                                         QStringLiteral("GeoPackage files (*.gpkg *.GPKG)")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("VERTICES"), QStringLiteral("Vertices")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("TRIANGLES"), QStringLiteral("Triangles")));
  addOutput(trianglesLayerOutput(QStringLiteral("TRIANGLES_LAYER"), QStringLiteral("Triangles layer")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("MAX_ERROR"), QStringLiteral("Maximum error (m), measured at every cell")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("RMSE"), QStringLiteral("RMSE (m)")));
  addParameterHelp(*this);
}

bool GreedyInsertionAlgorithm::prepareAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                                                QgsProcessingFeedback*) {
  readDemAndSamplingParameters(parameters, context);
  insert_ = InsertOptions();
  insert_.sample = sample_;
  insert_.candidates = parameterAsEnum(parameters, QStringLiteral("CANDIDATES"), context) == 1 ? InsertCandidates::Samples
                                                                                              : InsertCandidates::Cells;
  insert_.delaunayOnGrid = parameterAsEnum(parameters, QStringLiteral("DELAUNAY"), context) == 1;
  insert_.maxVertices = static_cast<std::size_t>(parameterAsInt(parameters, QStringLiteral("MAX_VERTICES"), context));
  insert_.maxTriangles = static_cast<std::size_t>(parameterAsInt(parameters, QStringLiteral("MAX_TRIANGLES"), context));
  const QVariant maxError = parameters.value(QStringLiteral("MAX_ERROR"));
  if (maxError.isValid() && !maxError.toString().isEmpty()) {
    bool number = false;
    insert_.maxError = maxError.toString().toDouble(&number);
    // parameterAsDouble would read "abc" as 0: an exact TIN nobody asked for.
    if (!number || insert_.maxError < 0)
      throw QgsProcessingException(QStringLiteral("MAX_ERROR must be a number of metres, 0 or more (got '%1'); leave it empty "
                                                  "for 1 m").arg(maxError.toString()));
  }
  else
    insert_.maxError = insert_.maxVertices || insert_.maxTriangles ? 0 : 1;
  if (insert_.maxVertices != 0 && insert_.maxVertices < 3)
    throw QgsProcessingException(QStringLiteral("MAX_VERTICES must be 3 or more, or 0 for no limit"));
  return true;
}

QVariantMap GreedyInsertionAlgorithm::processAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                                                       QgsProcessingFeedback* feedback) {
  const QString output = parameterAsFileOutput(parameters, QStringLiteral("OUTPUT"), context);
  const bool vertexIndex = parameterAsBoolean(parameters, QStringLiteral("VERTEX_INDEX"), context);
  // QGIS asks before overwriting a file; the core then keeps the file's other layers.
  const InsertSummary s = translateErrors(
      [&] {
        return runInsertJob(demSource_, output.toStdString(), insert_, true, processingFeedback(feedback, samplingParameterNames()), vertexIndex);
      },
      samplingParameterNames());
  feedback->pushInfo(QStringLiteral("%1 vertices, %2 triangles in %3; maximum error %4 m, RMSE %5 m over %6 cells")
                         .arg(s.vertices).arg(s.triangles).arg(QString::fromStdString(s.crsName))
                         .arg(s.measuredMaxError).arg(s.rmse).arg(s.measuredCells));
  if (!writesForALaterStepOnly(parameters, context))
    loadTinOnCompletion(context, output, outputBaseName(output, QStringLiteral("greedy insertion TIN")));
  QVariantMap outputs;
  outputs.insert(QStringLiteral("OUTPUT"), output);
  outputs.insert(QStringLiteral("TRIANGLES_LAYER"), gpkgLayer(output, QStringLiteral("triangles")));
  outputs.insert(QStringLiteral("VERTICES"), static_cast<qlonglong>(s.vertices));
  outputs.insert(QStringLiteral("TRIANGLES"), static_cast<qlonglong>(s.triangles));
  outputs.insert(QStringLiteral("MAX_ERROR"), s.measuredMaxError);
  outputs.insert(QStringLiteral("RMSE"), s.rmse);
  return outputs;
}

}  // namespace tinlod::qgis
