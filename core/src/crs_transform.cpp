// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/crs_transform.h"

#include <cpl_error.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>

#include "crs_scale.h"
#include "gdal_handles.h"
#include "layer_crs.h"
#include "text_and_paths.h"
#include "tinlod/error.h"

namespace tinlod {

struct CrsTransform::Impl {
  std::unique_ptr<OGRCoordinateTransformation> transform;  // null: identity
  std::unique_ptr<OGRCoordinateTransformation> inverse;
  std::string wkt;
  std::string name;
  std::string sourceWkt;
  std::string coverAdvice;  // what to use instead, when this CRS cannot project the DEM's whole extent
};

namespace {

std::string describe(const OGRSpatialReference& srs) {
  std::string name = crsLabel(srs);
  const char* authority = srs.GetAuthorityName(nullptr);
  const char* code = srs.GetAuthorityCode(nullptr);
  if (authority && code) name += std::string(" (") + authority + ":" + code + ")";
  return name;
}

bool isMetric(const OGRSpatialReference& srs) {
  return (srs.IsProjected() || srs.IsLocal()) && std::fabs(srs.GetLinearUnits() - 1.0) < 1e-9;
}

// A geographic CRS on coordinates that are no longitudes and latitudes (-s_srs EPSG:4326
// given for a DEM in UTM metres): PROJ would fail later with "Invalid latitude" noise and
// advice about -t_srs; the CRS that does not fit is named here.
void requireLonLat(const Dem& dem, const OGRSpatialReference& src, const std::string& sourceSrs) {
  if (!src.IsGeographic() || !dem.hasGeotransform) return;
  const std::array<double, 6>& gt = dem.wholeGeotransform();
  const double x[2] = {gt[0], gt[0] + dem.wholeWidth() * gt[1]}, y[2] = {gt[3], gt[3] + dem.wholeHeight() * gt[5]};
  const bool lonLat = std::min(x[0], x[1]) >= -540 && std::max(x[0], x[1]) <= 540 && std::min(y[0], y[1]) >= -90.5 &&
                      std::max(y[0], y[1]) <= 90.5;
  if (lonLat) return;
  const std::string extent = "x " + formatNumber(std::min(x[0], x[1])) + " to " + formatNumber(std::max(x[0], x[1])) + ", y " +
                             formatNumber(std::min(y[0], y[1])) + " to " + formatNumber(std::max(y[0], y[1]));
  throw Error("'" + dem.path + "' has coordinates (" + extent + ") that are no longitudes and latitudes, so " +
              (sourceSrs.empty() ? "its CRS " + describe(src) + " is wrong: name the right one with -s_srs"
                                 : "-s_srs " + sourceSrs + " (" + describe(src) + ") does not fit them: " +
                                       (dem.crsWkt.empty() ? "name the CRS they are in" : "leave -s_srs out to use the DEM's own CRS")) +
              " (QGIS: assign the layer's CRS)");
}

// The DEM's centre in longitude/latitude of its own datum, close enough to pick a UTM zone.
void centreLonLat(const Dem& dem, const OGRSpatialReference& src, double& lon, double& lat) {
  const std::array<double, 6>& gt = dem.wholeGeotransform();  // a tile picks its whole raster's zone
  lon = gt[0] + 0.5 * dem.wholeWidth() * gt[1];
  lat = gt[3] + 0.5 * dem.wholeHeight() * gt[5];
  if (src.IsGeographic()) return;
  std::unique_ptr<OGRSpatialReference> geog(src.CloneGeogCS());
  if (!geog)  // a local or engineering CRS has no longitude and latitude
    throw Error("'" + dem.path + "' has only a local CRS (" + describe(src) + ") in units that are not metres: name its "
                "CRS with -s_srs (e.g. -s_srs EPSG:4326 for degrees; QGIS: assign the layer's CRS), or a projected one with -t_srs");
  geog->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> ct(OGRCreateCoordinateTransformation(&src, geog.get()));
  if (!ct || !ct->Transform(1, &lon, &lat))
    throw Error("cannot find the longitude and latitude of the centre of '" + dem.path +
                "': name a projected CRS with -t_srs");
}

// Earth's ellipsoids all have a semi-major axis within a few kilometres of WGS 84's; a DEM
// of Mars (3396 km) or the Moon (1737 km) is on another body, which no UTM zone covers.
bool onEarth(const OGRSpatialReference& srs) {
  OGRErr err = OGRERR_NONE;
  const double a = srs.GetSemiMajor(&err);
  return err != OGRERR_NONE || std::fabs(a - 6378137.0) < 10000.0;
}

std::string bodyOf(const OGRSpatialReference& srs) {
  const char* datum = srs.GetAttrValue("DATUM");
  return datum ? datum : "its body";
}

// The CRSs tinlod fits are on WGS 84: a DEM of Mars is told what to look for.
std::string ownBodyAdvice(const OGRSpatialReference& src, const std::string& that) {
  return "choose a projected CRS of " + bodyOf(src) + " that " + that + ", with -t_srs";
}

// The automatic CRS of a DEM in degrees on another body: a transverse Mercator about its
// centre, true to scale on its meridian.
OGRSpatialReference transverseMercatorOnItsBody(const OGRSpatialReference& src, double lon) {
  std::unique_ptr<OGRSpatialReference> geog(src.CloneGeogCS());
  OGRSpatialReference dst;
  const double meridian = std::round(lon * 1000) / 1000;
  dst.SetProjCS(("Transverse Mercator " + formatNumber(meridian) + " on " + bodyOf(src)).c_str());
  if (geog) dst.CopyGeogCSFrom(geog.get());
  dst.SetTM(0, meridian, 1, 0, 0);
  dst.SetLinearUnits(SRS_UL_METER, 1.0);
  return dst;
}

OGRSpatialReference parseSrs(const std::string& definition, const std::string& role, const std::string& example) {
  OGRSpatialReference srs;
  CPLPushErrorHandler(CPLQuietErrorHandler);
  const OGRErr err = srs.SetFromUserInput(definition.c_str());
  CPLPopErrorHandler();
  if (err != OGRERR_NONE)
    throw Error(role + " '" + definition + "' is not a CRS GDAL understands: use e.g. " + example);
  return srs;
}

// Cells of under a tenth of a unit, all within longitudes and latitudes.
bool coordinatesLookLikeDegrees(const Dem& dem) {
  const double x0 = dem.geotransform[0], x1 = x0 + dem.width * dem.geotransform[1];
  const double y0 = dem.geotransform[3], y1 = y0 + dem.height * dem.geotransform[5];
  return dem.hasGeotransform && std::fabs(dem.geotransform[1]) < 0.1 && std::min(x0, x1) >= -180 &&
         std::max(x0, x1) <= 360 && std::min(y0, y1) >= -90 && std::max(y0, y1) <= 90;
}

// Degrees stored without a CRS (an .asc without .prj) would give a TIN a millionth of
// the right size: say so plainly.
void warnAboutMissingCrs(const Dem& dem, const ProgressRange& progress) {
  if (coordinatesLookLikeDegrees(dem))
    progress.warn("'" + dem.path + "' has no CRS and its coordinates look like degrees: name its CRS with -s_srs EPSG:4326 (QGIS: assign the layer's CRS), or the TIN will be in degrees");
  else
    progress.warn("'" + dem.path + "' has no CRS: its x and y units are taken as metres");
}

// The DEM's extent as a 9 x 9 grid of points, corners and edges included, in its CRS.
void extentGrid(const Dem& dem, std::vector<double>& x, std::vector<double>& y) {
  const std::array<double, 6>& gt = dem.wholeGeotransform();  // a tile weighs its whole raster
  constexpr int kSteps = 8;
  for (int i = 0; i <= kSteps; ++i)
    for (int j = 0; j <= kSteps; ++j) {
      x.push_back(gt[0] + dem.wholeWidth() * gt[1] * j / kSteps);
      y.push_back(gt[3] + dem.wholeHeight() * gt[5] * i / kSteps);
    }
}

// GDAL's first error while PROJ works ("hgridshift: could not find required grid(s)"), which
// names the cause, where its last ("Reprojection failed, err = 4098") does not.
class FirstGdalError {
 public:
  FirstGdalError() {
    CPLPushErrorHandlerEx(&FirstGdalError::keep, this);
    CPLSetCurrentErrorHandlerCatchDebug(FALSE);  // a user's CPL_DEBUG output still shows
  }
  ~FirstGdalError() { CPLPopErrorHandler(); }
  FirstGdalError(const FirstGdalError&) = delete;
  FirstGdalError& operator=(const FirstGdalError&) = delete;
  const std::string& message() const { return first_; }

 private:
  static void CPL_STDCALL keep(CPLErr level, CPLErrorNum, const char* message) {
    auto* self = static_cast<FirstGdalError*>(CPLGetErrorHandlerUserData());
    if (level >= CE_Failure && self->first_.empty() && message) self->first_ = message;
  }
  std::string first_;
};

// How many of the points PROJ cannot transform, transforming the others in place, and PROJ's
// reason for the first. GDAL reports each failed point: the caller says it once.
std::size_t transformMisses(OGRCoordinateTransformation& ct, std::vector<double>& x, std::vector<double>& y,
                            std::string* reason = nullptr) {
  std::vector<int> ok(x.size());
  const FirstGdalError first;
  const bool done = ct.Transform(x.size(), x.data(), y.data(), nullptr, ok.data());
  const auto misses = static_cast<std::size_t>(std::count(ok.begin(), ok.end(), 0));
  if (reason) *reason = first.message();
  return done || misses > 0 ? misses : x.size();
}

// A UTM zone stretches distances by under 0.3 % within 500 km of its central meridian:
// far below the 1 % worth a warning, so PROJ's scale factors, which cost a PROJ
// database context and a search for operations of their own, are not needed.
bool withinUtmZone(const OGRSpatialReference& dst, const std::vector<double>& easting) {
  return dst.GetUTMZone() != 0 &&
         std::all_of(easting.begin(), easting.end(), [](double e) { return std::fabs(e - 500000.0) <= 500000.0; });
}

std::vector<LonLat> lonLatOf(const OGRSpatialReference& src, std::vector<double> x, std::vector<double> y) {
  std::vector<LonLat> out;
  if (!src.IsGeographic()) {
    std::unique_ptr<OGRSpatialReference> geog(src.CloneGeogCS());
    if (!geog) return out;  // a local CRS is nowhere on Earth
    geog->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRCoordinateTransformation> ct(OGRCreateCoordinateTransformation(&src, geog.get()));
    std::vector<int> ok(x.size());
    if (!ct || !ct->Transform(x.size(), x.data(), y.data(), nullptr, ok.data())) return out;
    for (std::size_t i = 0; i < x.size(); ++i)
      if (ok[i]) out.push_back({x[i], y[i]});
    return out;
  }
  for (std::size_t i = 0; i < x.size(); ++i) out.push_back({x[i], y[i]});
  return out;
}

// Metres in a CRS that stretches distances are not metres on the ground: slopes, areas
// and volumes come out wrong by the same factor. Measured over the whole extent: a DEM
// wider than a UTM zone is true to scale at its centre and not at its sides. A CRS that
// cannot project part of the extent (a hemisphere in one UTM zone) fails the run where
// the DEM has data there, after the DEM is read: said here first, with a CRS that covers
// it. Returns that advice, for the run's error; empty when the CRS projects the extent.
std::string warnAboutScale(const Dem& dem, const OGRSpatialReference& src, const OGRSpatialReference& dst,
                           OGRCoordinateTransformation* toTin, const std::string& targetWkt,
                           const std::string& gdalSaid, const ProgressRange& progress) {
  if (!dst.IsProjected() || !dem.hasGeotransform) return {};
  std::vector<double> x, y;
  extentGrid(dem, x, y);
  // A raster reaching a hair beyond a pole (requireLonLat allows half a degree) is weighed at it.
  if (src.IsGeographic())
    for (double& lat : y) lat = std::clamp(lat, -90.0, 90.0);
  std::vector<double> easting = x, northing = y;
  std::string reason;
  const std::size_t misses = toTin ? transformMisses(*toTin, easting, northing, &reason) : 0;
  if (misses == 0 && withinUtmZone(dst, easting)) return {};
  const std::vector<LonLat> points = lonLatOf(src, x, y);
  LonLat centre;
  bool placed = !points.empty();
  try {
    if (placed) centreLonLat(dem, src, centre.lon, centre.lat);
  } catch (const Error&) {
    placed = false;
  }
  const std::string covering = !placed          ? "choose a CRS that covers the DEM with -t_srs"
                               : onEarth(src) ? coverAdvice(points, centre)
                                              : ownBodyAdvice(src, "covers it");
  if (misses == x.size())  // nowhere near the DEM, or not at all: PROJ's first word says which
    throw Error("PROJ cannot transform any point of the DEM to " + describe(dst) + " (" +
                (gdalSaid.empty() ? reason : gdalSaid) + "): " + covering);
  if (!placed) return {};
  if (misses > 0) {
    progress.warn(describe(dst) + " cannot project the whole DEM: PROJ fails at " + std::to_string(misses) + " of " +
                  std::to_string(x.size()) + " points spread over its extent, and the run fails if the DEM has data "
                  "there: " + covering);
    return covering;
  }
  const double error = worstScaleError(targetWkt, points);
  if (!(error > 0.01)) return {};  // NaN: PROJ cannot tell
  progress.warn(describe(dst) + " stretches distances by " + (error >= 10 ? "" : "up to ") + percentText(error) +
                " over the DEM, so slopes, areas and volumes of the TIN are off by as much: " +
                (onEarth(src) ? scaleAdvice(points, centre, error) : ownBodyAdvice(src, "keeps it within 1 % of true scale")));
  return {};
}

OGRSpatialReference parseTarget(const std::string& targetSrs) {
  OGRSpatialReference dst = parseSrs(targetSrs, "target CRS", "EPSG:32632 (a UTM zone)");
  if (!isMetric(dst))
    throw Error("target CRS " + describe(dst) +
                " is not a projected CRS in metres: tinlod needs metric x and y, e.g. a UTM zone");
  return dst;
}

}  // namespace

int utmEpsgFor(double lon, double lat) {
  const double wrapped = std::fmod(std::fmod(lon + 180.0, 360.0) + 360.0, 360.0);
  const int zone = std::clamp(static_cast<int>(std::floor(wrapped / 6.0)) + 1, 1, 60);
  return (lat >= 0 ? 32600 : 32700) + zone;
}

CrsTransform::CrsTransform(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
CrsTransform::CrsTransform(CrsTransform&&) noexcept = default;
CrsTransform& CrsTransform::operator=(CrsTransform&&) noexcept = default;
CrsTransform::~CrsTransform() = default;

bool CrsTransform::isIdentity() const { return !impl_->transform; }
const std::string& CrsTransform::targetWkt() const { return impl_->wkt; }
const std::string& CrsTransform::targetName() const { return impl_->name; }
const std::string& CrsTransform::sourceWkt() const { return impl_->sourceWkt; }

CrsTransform CrsTransform::forDem(const Dem& dem, const std::string& sourceSrs, const std::string& targetSrs,
                                  const ProgressRange& progress) {
  // A CRS PROJ cannot use (a grid file missing) makes GDAL report the same errors at every
  // question asked of it; each failure is said below, once, in the user's terms.
  const FirstGdalError gdalSaid;
  auto impl = std::make_unique<Impl>();
  OGRSpatialReference src;
  bool hasSrc = !dem.crsWkt.empty() && src.importFromWkt(dem.crsWkt.c_str()) == OGRERR_NONE;
  if (!sourceSrs.empty()) {
    src = parseSrs(sourceSrs, "source CRS", "EPSG:4326 (longitude/latitude)");
    hasSrc = true;
  }
  src.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (hasSrc) requireLonLat(dem, src, sourceSrs);
  if (hasSrc) impl->sourceWkt = sourceSrs.empty() ? dem.crsWkt : wkt2(src);

  OGRSpatialReference dst;
  if (!targetSrs.empty()) {
    dst = parseTarget(targetSrs);
    // A local CRS (such as a file's "unnamed" engineering one) ties the grid to no place on Earth.
    if (!hasSrc || (src.IsLocal() && !src.IsSame(&dst)))
      throw Error("'" + dem.path + "' has no CRS" + (hasSrc ? " (only a local one, " + describe(src) + ")" : "") +
                  ", so it cannot be transformed to " + describe(dst) +
                  ": name its CRS with -s_srs, e.g. -s_srs EPSG:4326 (QGIS: assign the layer's CRS)");
  } else if (!hasSrc) {
    warnAboutMissingCrs(dem, progress);
    impl->name = "no CRS";
    return CrsTransform(std::move(impl));
  } else if (isMetric(src)) {
    // Degrees under a CRS in metres (a layer given the wrong CRS in QGIS) made a TIN 0.12 m
    // wide without a word.
    if (coordinatesLookLikeDegrees(dem))
      progress.warn("'" + dem.path + "' is taken as in " + describe(src) + ", a CRS in metres, but its cells are " +
                    formatNumber(std::fabs(dem.geotransform[1])) + " m and its coordinates look like degrees: if they "
                    "are, name its CRS with -s_srs EPSG:4326 (QGIS: assign the layer's CRS), or the TIN will span "
                    "as many metres as the DEM spans degrees");
    dst = src;
  } else {
    double lon = 0, lat = 0;
    centreLonLat(dem, src, lon, lat);
    if (onEarth(src))
      dst.importFromEPSG(utmEpsgFor(lon, lat));
    else
      dst = transverseMercatorOnItsBody(src, lon);
    progress.inform("'" + dem.path + "' is in " + describe(src) +
                    ", which is not metric: points are transformed to " + describe(dst));
  }
  dst.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  impl->wkt = wkt2(dst);
  impl->name = describe(dst);
  if (hasSrc && onEarth(src) != onEarth(dst))
    throw Error("'" + dem.path + "' is in " + describe(src) + ", on " + (onEarth(src) ? "Earth" : bodyOf(src)) + ", and " +
                impl->name + " is on " + (onEarth(dst) ? "Earth" : bodyOf(dst)) +
                ": give -t_srs a projected CRS of the DEM's own body, or leave it out for a transverse Mercator on it");
  if (!src.IsSame(&dst)) {
    {
      const CPLErrorHandlerPusher quiet(CPLQuietErrorHandler);  // the error below says it, once
      impl->transform.reset(OGRCreateCoordinateTransformation(&src, &dst));
    }
    if (!impl->transform) {
      const std::string why = CPLGetLastErrorMsg();
      // GDAL quotes both CRSs' whole WKT after "from".
      throw Error("no transformation from " + describe(src) + " to " + impl->name + ": " + why.substr(0, why.find(" from `")));
    }
  }
  impl->coverAdvice = warnAboutScale(dem, src, dst, impl->transform.get(), impl->wkt, gdalSaid.message(), progress);
  return CrsTransform(std::move(impl));
}

namespace {

bool transformAll(OGRCoordinateTransformation& ct, std::vector<double>& x, std::vector<double>& y) {
  return transformMisses(ct, x, y) == 0;
}

}  // namespace

double CrsTransform::groundDistance(double x0, double y0, double x1, double y1) const {
  std::vector<double> x{x0, x1}, y{y0, y1};
  apply(x, y);
  return std::hypot(x[1] - x[0], y[1] - y[0]);
}

void CrsTransform::apply(std::vector<double>& x, std::vector<double>& y) const {
  if (!impl_->transform) return;
  std::string reason;
  const std::size_t misses = transformMisses(*impl_->transform, x, y, &reason);
  if (misses > 0)
    throw Error("PROJ could not transform " + std::to_string(misses) + " of " + std::to_string(x.size()) +
                " points of the DEM to " + impl_->name + (reason.empty() ? "" : " (" + reason + ")") + ": " +
                (impl_->coverAdvice.empty() ? "choose a CRS that covers the DEM with -t_srs" : impl_->coverAdvice));
}

void CrsTransform::applyInverse(std::vector<double>& x, std::vector<double>& y) const {
  if (!impl_->transform) return;
  if (!impl_->inverse) impl_->inverse.reset(impl_->transform->GetInverse());
  if (!impl_->inverse || !transformAll(*impl_->inverse, x, y))
    throw Error("PROJ could not transform points of " + impl_->name + " back to the DEM's CRS");
}

}  // namespace tinlod
