// SPDX-License-Identifier: GPL-3.0-or-later
#include "dem_algorithm.h"

#include <qgsprocessingparameters.h>
#include <qgsrasterlayer.h>

#include <cmath>
#include <memory>

#include "parameter_decimals.h"

namespace tinlod::qgis {
namespace {

// The definition handed to the core: the authority id where there is one (short in
// messages), WKT otherwise. Geographic or non-metre CRSs are refused before the run.
std::string srsText(const QgsCoordinateReferenceSystem& crs) {
  return (crs.authid().isEmpty() ? crs.toWkt(QgsCoordinateReferenceSystem::WKT_PREFERRED) : crs.authid()).toStdString();
}

std::string targetSrs(const QgsCoordinateReferenceSystem& crs) {
  if (!crs.isValid()) return {};
  if (crs.isGeographic() || crs.mapUnits() != QgsUnitTypes::DistanceMeters)
    throw QgsProcessingException(QStringLiteral("TARGET_CRS must be a projected CRS in metres, such as a UTM zone; "
                                                "%1 is not").arg(crs.userFriendlyIdentifier()));
  return srsText(crs);
}

// QGIS reads a PROJ string only after "PROJ:" and takes anything it cannot read as no CRS at
// all: the run went on in the automatic CRS. Such text goes to the core as -t_srs does, which
// reads what GDAL reads (the "+proj=..." its warnings advise) and refuses the rest by name.
std::string targetSrs(const QgsCoordinateReferenceSystem& crs, const QVariant& value) {
  if (crs.isValid() || value.userType() != QMetaType::QString) return targetSrs(crs);
  return value.toString().trimmed().toStdString();
}

// A CRS the user gave the layer in QGIS (Layer Properties, or QGIS's question for a file
// without one) where its file has none or another: the DEM's, as -s_srs on the command line.
std::string assignedSrs(QgsRasterLayer& layer) {
  const QgsCoordinateReferenceSystem crs = layer.crs();
  if (!crs.isValid() || !layer.dataProvider()) return {};
  const QgsCoordinateReferenceSystem file = layer.dataProvider()->crs();
  return file.isValid() && file == crs ? std::string() : srsText(crs);
}

}  // namespace

QgsProcessingParameterDefinition* DemAlgorithm::advanced(QgsProcessingParameterDefinition* p) {
  p->setFlags(p->flags() | QgsProcessingParameterDefinition::FlagAdvanced);
  return p;
}

void DemAlgorithm::addDemParameters(bool rangeOfTheGeoPackage) {
  addParameter(new QgsProcessingParameterRasterLayer(QStringLiteral("INPUT"), QStringLiteral("DEM")));
  // Optional with a default: qgis_process 3.22 reports a mandatory band as missing
  // even when it has a default value.
  // Against a GeoPackage an empty band means the one it was sampled from: no default.
  addParameter(new QgsProcessingParameterBand(QStringLiteral("BAND"), QStringLiteral("Band"),
                                              rangeOfTheGeoPackage ? QVariant() : QVariant(SampleOptions().band),
                                              QStringLiteral("INPUT"), true));
  const HeightRange defaults;
  const QVariant range = rangeOfTheGeoPackage ? QVariant() : QVariant(QStringLiteral("%1,%2").arg(defaults.min).arg(defaults.max));
  addParameter(advanced(new QgsProcessingParameterRange(
      QStringLiteral("VALID_RANGE"),
      rangeOfTheGeoPackage ? QStringLiteral("Valid heights (metres; empty: the range the GeoPackage was made with)")
                           : QStringLiteral("Valid heights (metres; others are nodata)"),
      QgsProcessingParameterNumber::Double, range, true)));
}

void DemAlgorithm::addDemAndSamplingParameters() {
  const SampleOptions defaults;
  addDemParameters();
  addParameter(new QgsProcessingParameterNumber(QStringLiteral("BLOCK"), QStringLiteral("Block size k (one sample per k x k cells)"),
                                                QgsProcessingParameterNumber::Integer, defaults.block, false, 1, 1000));
  auto* jitter = decimals(2, new QgsProcessingParameterNumber(QStringLiteral("JITTER"), QStringLiteral("Jitter (metres)"),
                                                  QgsProcessingParameterNumber::Double, defaults.jitter, false, 0.0, 100.0));
  addParameter(advanced(jitter));
  addParameter(advanced(new QgsProcessingParameterNumber(QStringLiteral("SEED"), QStringLiteral("Random seed"),
                                                         QgsProcessingParameterNumber::Integer,
                                                         static_cast<int>(defaults.seed), false, 0, 2147483647)));
  addParameter(advanced(new QgsProcessingParameterCrs(QStringLiteral("TARGET_CRS"),
                                                      QStringLiteral("Target CRS (default: automatic)"), QVariant(), true)));
}

void DemAlgorithm::readDemAndSamplingParameters(const QVariantMap& parameters, QgsProcessingContext& context) {
  readDemParameters(parameters, context, SampleOptions().band);
  sample_.block = parameterAsInt(parameters, QStringLiteral("BLOCK"), context);
  sample_.jitter = parameterAsDouble(parameters, QStringLiteral("JITTER"), context);
  sample_.seed = static_cast<std::uint64_t>(parameterAsInt(parameters, QStringLiteral("SEED"), context));
  sample_.targetSrs = targetSrs(parameterAsCrs(parameters, QStringLiteral("TARGET_CRS"), context),
                                parameters.value(QStringLiteral("TARGET_CRS")));
}

void DemAlgorithm::readDemParameters(const QVariantMap& parameters, QgsProcessingContext& context, int emptyBand) {
  QgsRasterLayer* layer = parameterAsRasterLayer(parameters, QStringLiteral("INPUT"), context);
  if (!layer) throw QgsProcessingException(invalidRasterError(parameters, QStringLiteral("INPUT")));
  if (layer->providerType() != QLatin1String("gdal"))
    throw QgsProcessingException(QStringLiteral("INPUT must be a raster file GDAL reads; '%1' comes from the %2 provider: "
                                                "save it as a GeoTIFF first").arg(layer->name(), layer->providerType()));
  const QVariant bandValue = parameters.value(QStringLiteral("BAND"));
  const int band = bandValue.isValid() && !bandValue.toString().isEmpty()
                       ? parameterAsInt(parameters, QStringLiteral("BAND"), context)
                       : emptyBand;
  if (band != emptyBand && (band < 1 || band > layer->bandCount()))
    throw QgsProcessingException(QStringLiteral("Invalid band number for BAND (%1): valid values for input raster are 1 to %2")
                                     .arg(band).arg(layer->bandCount()));
  demSource_ = layer->source().toStdString();
  sample_.sourceSrs = assignedSrs(*layer);
  sample_.band = band;
  validHeights_ = validRange(parameters, context);
  sample_.validHeights = validHeights_.value_or(HeightRange{});
}

std::optional<HeightRange> DemAlgorithm::validRange(const QVariantMap& parameters, QgsProcessingContext& context) {
  const QVariant value = parameters.value(QStringLiteral("VALID_RANGE"));
  if (!value.isValid() || value.toString().isEmpty()) return std::nullopt;
  const QList<double> range = parameterAsRange(parameters, QStringLiteral("VALID_RANGE"), context);
  // The dialog's "Not set" comes as "None,None": both ends missing is no range at all.
  if (range.size() == 2 && std::isnan(range[0]) && std::isnan(range[1])) return std::nullopt;
  if (range.size() != 2 || !std::isfinite(range[0]) || !std::isfinite(range[1]) || !(range[0] < range[1]))
    throw QgsProcessingException(QStringLiteral("Invalid range for VALID_RANGE (%1): give the lowest and the highest valid "
                                                "height in metres, the lower first, e.g. -12000,9000")
                                     .arg(value.toString()));
  return HeightRange{range[0], range[1]};
}

QString DemAlgorithm::samplingHelp() {
  return QStringLiteral(
      "Sampling: one random valid cell is taken from each block of k x k cells (the study used 3 x 3; 1 "
      "takes every cell), and every valid cell on the outline of the valid area is added so that "
      "the TIN covers the DEM's whole valid extent. Each point's x and y are moved by a random "
      "offset in [0, jitter) metres so that no four points are cocircular; the seed makes runs "
      "reproducible. The points are triangulated with CGAL's exact-predicate Delaunay "
      "triangulation. Nodata cells (declared nodata, NaN, masks) never become vertices, and no "
      "triangle spans them: holes stay holes. Heights outside the valid heights (by default -12000 to "
      "9000 m, the Earth's range) and infinite ones are nodata too, counted in one warning: fill values a "
      "file does not declare, such as 1e30 or -32768, never become vertices. A band of complex numbers is "
      "refused.\n\n"
      "Units: heights are taken as metres and are never resampled. A DEM in a geographic CRS "
      "(most SRTM data) has its points' x and y transformed to the UTM zone of its centre, or to "
      "the target CRS given, which must be projected and in metres. A DEM without a CRS is taken "
      "as metric.\n\n"
      "Band: empty means band 1. Target CRS: empty means automatic (the DEM's own CRS when it is "
      "metric, else the UTM zone of its centre); a CRS that stretches distances by more than 1 % "
      "over the DEM draws a warning naming one to use.");
}

ParameterNames DemAlgorithm::demParameterNames(const ParameterNames& more) {
  const ParameterNames names{{QStringLiteral("-b"), QStringLiteral("BAND")}, {QStringLiteral("-valid_range"), QStringLiteral("VALID_RANGE")}};
  return names + more;
}

ParameterNames DemAlgorithm::samplingParameterNames(const ParameterNames& more) {
  const ParameterNames names{{QStringLiteral("-block"), QStringLiteral("BLOCK")}, {QStringLiteral("-jitter"), QStringLiteral("JITTER")},
                             {QStringLiteral("-seed"), QStringLiteral("SEED")}, {QStringLiteral("-t_srs"), QStringLiteral("TARGET_CRS")}};
  return demParameterNames(names + more);
}

}  // namespace tinlod::qgis
