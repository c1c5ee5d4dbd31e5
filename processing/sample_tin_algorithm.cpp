// SPDX-License-Identifier: GPL-3.0-or-later
#include "sample_tin_algorithm.h"

#include <qgsprocessingparameters.h>
#include <qgsprocessingoutputs.h>

#include "group_icon.h"
#include "help_page.h"
#include "layer_placement.h"
#include "processing_feedback.h"
#include "tin_layer_output.h"
#include "tin_layer_style.h"
#include "tinlod/sample_job.h"
#include "vertex_index_parameter.h"

namespace tinlod::qgis {

QString SampleTinAlgorithm::name() const { return QStringLiteral("sampletin"); }
QString SampleTinAlgorithm::displayName() const { return QStringLiteral("Sample TIN from DEM"); }
QString SampleTinAlgorithm::group() const { return QStringLiteral("TIN construction"); }
QString SampleTinAlgorithm::groupId() const { return QStringLiteral("construction"); }
QStringList SampleTinAlgorithm::tags() const {
  return QStringLiteral("tin,dem,delaunay,triangulation,sample,terrain,mesh").split(',');
}

QString SampleTinAlgorithm::shortDescription() const {
  return QStringLiteral("A Delaunay TIN of one random cell per k x k block of a DEM, written as vertex and triangle layers.");
}
QIcon SampleTinAlgorithm::icon() const { return groupIcon(groupId()); }
QString SampleTinAlgorithm::helpUrl() const { return helpPageUrl(name()); }

QString SampleTinAlgorithm::shortHelpString() const {
  return QStringLiteral(
             "Samples a DEM into a Delaunay TIN (triangulated irregular network), the original TIN of "
             "a tinlod hierarchy.\n\n") +
         samplingHelp() +
         QStringLiteral(
             "\n\nOutput: a GeoPackage with a 'vertices' layer (PointZ: id, source row and column, outline "
             "flag) and a 'triangles' layer (PolygonZ, one feature per triangle with its three vertex "
             "ids; ids equal the fid). An existing GeoPackage keeps its other layers; tinlod's own layers "
             "are replaced. A failed or cancelled run leaves the file as it was.");
}

SampleTinAlgorithm* SampleTinAlgorithm::createInstance() const { return new SampleTinAlgorithm(); }

void SampleTinAlgorithm::initAlgorithm(const QVariantMap&) {
  addDemAndSamplingParameters();
  addParameter(vertexIndexParameter());
  addParameter(new QgsProcessingParameterFileDestination(QStringLiteral("OUTPUT"), QStringLiteral("TIN GeoPackage"),
                                                         QStringLiteral("GeoPackage files (*.gpkg *.GPKG)")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("VERTICES"), QStringLiteral("Vertices")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("TRIANGLES"), QStringLiteral("Triangles")));
  addOutput(trianglesLayerOutput(QStringLiteral("TRIANGLES_LAYER"), QStringLiteral("Triangles layer")));
  addParameterHelp(*this);
}

bool SampleTinAlgorithm::prepareAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                                          QgsProcessingFeedback*) {
  readDemAndSamplingParameters(parameters, context);
  return true;
}

QVariantMap SampleTinAlgorithm::processAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                                                 QgsProcessingFeedback* feedback) {
  const QString output = parameterAsFileOutput(parameters, QStringLiteral("OUTPUT"), context);
  const bool vertexIndex = parameterAsBoolean(parameters, QStringLiteral("VERTEX_INDEX"), context);
  // QGIS asks before overwriting a file; the core then keeps the file's other layers.
  const SampleSummary summary = translateErrors(
      [&] {
        return runSampleJob(demSource_, output.toStdString(), sample_, true, processingFeedback(feedback, samplingParameterNames()), vertexIndex);
      },
      samplingParameterNames());
  feedback->pushInfo(QStringLiteral("%1 vertices, %2 triangles in %3")
                         .arg(summary.vertices).arg(summary.triangles).arg(QString::fromStdString(summary.crsName)));
  if (!writesForALaterStepOnly(parameters, context))
    loadTinOnCompletion(context, output, outputBaseName(output, QStringLiteral("sampled TIN")));
  QVariantMap outputs;
  outputs.insert(QStringLiteral("OUTPUT"), output);
  outputs.insert(QStringLiteral("TRIANGLES_LAYER"), gpkgLayer(output, QStringLiteral("triangles")));
  outputs.insert(QStringLiteral("VERTICES"), static_cast<qlonglong>(summary.vertices));
  outputs.insert(QStringLiteral("TRIANGLES"), static_cast<qlonglong>(summary.triangles));
  return outputs;
}

}  // namespace tinlod::qgis
