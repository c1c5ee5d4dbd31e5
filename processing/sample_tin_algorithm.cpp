// SPDX-License-Identifier: GPL-3.0-or-later
#include "sample_tin_algorithm.h"

#include <qgsprocessingparameters.h>
#include <qgsprocessingoutputs.h>
#include <qgsrasterlayer.h>

#include "processing_feedback.h"
#include "tin_layer_style.h"
#include "tinlod/sample_job.h"

namespace tinlod::qgis {

QString SampleTinAlgorithm::name() const { return QStringLiteral("sampletin"); }
QString SampleTinAlgorithm::displayName() const { return QStringLiteral("Sample TIN from DEM"); }
QString SampleTinAlgorithm::group() const { return QStringLiteral("TIN construction"); }
QString SampleTinAlgorithm::groupId() const { return QStringLiteral("construction"); }
QStringList SampleTinAlgorithm::tags() const {
  return QStringLiteral("tin,dem,delaunay,triangulation,sample,terrain,mesh").split(',');
}

QString SampleTinAlgorithm::shortHelpString() const {
  return QStringLiteral(
      "Samples a DEM into a Delaunay TIN (triangulated irregular network), the original TIN of "
      "a tinlod hierarchy.\n\n"
      "One random valid cell is taken from each block of k x k cells (the study used 3 x 3; 1 "
      "takes every cell), and every valid cell on the outline of the valid area is added so that "
      "the TIN covers the DEM's whole valid extent. Each point's x and y are moved by a random "
      "offset in [0, jitter) metres so that no four points are cocircular; the seed makes runs "
      "reproducible. The points are triangulated with CGAL's exact-predicate Delaunay "
      "triangulation.\n\n"
      "Nodata cells (declared nodata, NaN, masks) never become vertices, and no triangle spans "
      "them: holes stay holes.\n\n"
      "Units: heights are taken as metres and are never resampled. A DEM in a geographic CRS "
      "(most SRTM data) has its points' x and y transformed to the UTM zone of its centre, or to "
      "the target CRS given, which must be projected and in metres. A DEM without a CRS is taken "
      "as metric.\n\n"
      "Band: empty means band 1. Target CRS: empty means automatic (the DEM's own CRS when it is "
      "metric, else the UTM zone of its centre); a CRS that distorts distances by more than 1 % "
      "there draws a warning.\n\n"
      "Output: a GeoPackage with a 'vertices' layer (PointZ: id, source row and column, outline "
      "flag) and a 'triangles' layer (PolygonZ, one feature per triangle with its three vertex "
      "ids). An existing GeoPackage keeps its other layers; tinlod's own layers are replaced. A "
      "failed or cancelled run leaves the file as it was.");
}

namespace {

// The definition handed to the core: the authority id where there is one (short in
// messages), WKT otherwise. Geographic or non-metre CRSs are refused before the run.
std::string targetSrs(const QgsCoordinateReferenceSystem& crs) {
  if (!crs.isValid()) return {};
  if (crs.isGeographic() || crs.mapUnits() != QgsUnitTypes::DistanceMeters)
    throw QgsProcessingException(QStringLiteral("TARGET_CRS must be a projected CRS in metres, such as a UTM zone; "
                                                "%1 is not").arg(crs.userFriendlyIdentifier()));
  return (crs.authid().isEmpty() ? crs.toWkt(QgsCoordinateReferenceSystem::WKT_PREFERRED) : crs.authid()).toStdString();
}

}  // namespace

SampleTinAlgorithm* SampleTinAlgorithm::createInstance() const { return new SampleTinAlgorithm(); }

void SampleTinAlgorithm::initAlgorithm(const QVariantMap&) {
  const SampleOptions defaults;
  addParameter(new QgsProcessingParameterRasterLayer(QStringLiteral("INPUT"), QStringLiteral("DEM")));
  // Optional with a default: qgis_process 3.22 reports a mandatory band as missing
  // even when it has a default value.
  addParameter(new QgsProcessingParameterBand(QStringLiteral("BAND"), QStringLiteral("Band"), defaults.band,
                                              QStringLiteral("INPUT"), true));
  addParameter(new QgsProcessingParameterNumber(QStringLiteral("BLOCK"), QStringLiteral("Block size k (one sample per k x k cells)"),
                                                QgsProcessingParameterNumber::Integer, defaults.block, false, 1, 1000));
  auto jitter = std::make_unique<QgsProcessingParameterNumber>(
      QStringLiteral("JITTER"), QStringLiteral("Jitter (metres)"), QgsProcessingParameterNumber::Double,
      defaults.jitter, false, 0.0, 100.0);
  jitter->setMetadata({{QStringLiteral("widget_wrapper"), QVariantMap{{QStringLiteral("decimals"), 2}}}});
  auto seed = std::make_unique<QgsProcessingParameterNumber>(
      QStringLiteral("SEED"), QStringLiteral("Random seed"), QgsProcessingParameterNumber::Integer,
      static_cast<int>(defaults.seed), false, 0, 2147483647);
  auto crs = std::make_unique<QgsProcessingParameterCrs>(
      QStringLiteral("TARGET_CRS"), QStringLiteral("Target CRS (default: automatic)"), QVariant(), true);
  for (QgsProcessingParameterDefinition* p : {static_cast<QgsProcessingParameterDefinition*>(jitter.get()),
                                              static_cast<QgsProcessingParameterDefinition*>(seed.get()),
                                              static_cast<QgsProcessingParameterDefinition*>(crs.get())})
    p->setFlags(p->flags() | QgsProcessingParameterDefinition::FlagAdvanced);
  addParameter(jitter.release());
  addParameter(seed.release());
  addParameter(crs.release());
  addParameter(new QgsProcessingParameterFileDestination(QStringLiteral("OUTPUT"), QStringLiteral("TIN GeoPackage"),
                                                         QStringLiteral("GeoPackage files (*.gpkg *.GPKG)")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("VERTICES"), QStringLiteral("Vertices")));
  addOutput(new QgsProcessingOutputNumber(QStringLiteral("TRIANGLES"), QStringLiteral("Triangles")));
}

bool SampleTinAlgorithm::prepareAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                                          QgsProcessingFeedback*) {
  QgsRasterLayer* layer = parameterAsRasterLayer(parameters, QStringLiteral("INPUT"), context);
  if (!layer) throw QgsProcessingException(invalidRasterError(parameters, QStringLiteral("INPUT")));
  if (layer->providerType() != QLatin1String("gdal"))
    throw QgsProcessingException(QStringLiteral("INPUT must be a raster file GDAL reads; '%1' comes from the %2 provider: "
                                                "save it as a GeoTIFF first").arg(layer->name(), layer->providerType()));
  const QVariant bandValue = parameters.value(QStringLiteral("BAND"));
  const int band = bandValue.isValid() && !bandValue.toString().isEmpty()
                       ? parameterAsInt(parameters, QStringLiteral("BAND"), context)
                       : SampleOptions().band;
  if (band < 1 || band > layer->bandCount())
    throw QgsProcessingException(QStringLiteral("Invalid band number for BAND (%1): valid values for input raster are 1 to %2")
                                     .arg(band).arg(layer->bandCount()));
  demSource_ = layer->source().toStdString();
  options_.band = band;
  options_.block = parameterAsInt(parameters, QStringLiteral("BLOCK"), context);
  options_.jitter = parameterAsDouble(parameters, QStringLiteral("JITTER"), context);
  options_.seed = static_cast<std::uint64_t>(parameterAsInt(parameters, QStringLiteral("SEED"), context));
  options_.targetSrs = targetSrs(parameterAsCrs(parameters, QStringLiteral("TARGET_CRS"), context));
  return true;
}

QVariantMap SampleTinAlgorithm::processAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                                                 QgsProcessingFeedback* feedback) {
  const QString output = parameterAsFileOutput(parameters, QStringLiteral("OUTPUT"), context);
  // QGIS asks before overwriting a file; the core then keeps the file's other layers.
  const SampleSummary summary = translateErrors([&] {
    return runSampleJob(demSource_, output.toStdString(), options_, true, processingFeedback(feedback));
  });
  feedback->pushInfo(QStringLiteral("%1 vertices, %2 triangles in %3")
                         .arg(summary.vertices).arg(summary.triangles).arg(QString::fromStdString(summary.crsName)));
  for (const QString& layer : {QStringLiteral("vertices"), QStringLiteral("triangles")})
    loadTinLayerOnCompletion(context, output, layer, QStringLiteral("OUTPUT"));
  QVariantMap outputs;
  outputs.insert(QStringLiteral("OUTPUT"), output);
  outputs.insert(QStringLiteral("VERTICES"), static_cast<qlonglong>(summary.vertices));
  outputs.insert(QStringLiteral("TRIANGLES"), static_cast<qlonglong>(summary.triangles));
  return outputs;
}

}  // namespace tinlod::qgis
