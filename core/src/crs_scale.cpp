// SPDX-License-Identifier: GPL-3.0-or-later
#include "crs_scale.h"

#include <proj.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "text_and_paths.h"
#include "tinlod/crs_transform.h"

namespace tinlod {

namespace {

struct ScaleRange {
  double low = std::numeric_limits<double>::infinity();
  double high = -std::numeric_limits<double>::infinity();
  bool complete = false;  // every point projected: a CRS that cannot hold the DEM is no advice
};

using PjPtr = std::unique_ptr<PJ, decltype(&proj_destroy)>;

// The projected CRS in a definition: itself, a bound CRS's source, a compound CRS's
// horizontal part (a DEM's CRS with heights, EPSG:25832+7837).
PjPtr projectedPart(PJ_CONTEXT* ctx, PjPtr pj) {
  for (int depth = 0; pj && depth < 4; ++depth) {  // a bound CRS may wrap a compound one
    const PJ_TYPE type = proj_get_type(pj.get());
    if (type == PJ_TYPE_PROJECTED_CRS) return pj;
    if (type == PJ_TYPE_COMPOUND_CRS)
      pj = PjPtr(proj_crs_get_sub_crs(ctx, pj.get(), 0), proj_destroy);
    else if (type == PJ_TYPE_BOUND_CRS)
      pj = PjPtr(proj_get_source_crs(ctx, pj.get()), proj_destroy);
    else
      break;
  }
  return PjPtr(nullptr, proj_destroy);
}

// The projection of a projected CRS, taking radians as proj_factors gives them: proj_factors
// on the CRS itself looks an operation up again at every point (15 ms each), and the CRS's
// own conversion takes degrees in the CRS's axis order. A CRS no PROJ string expresses is
// kept as it is: slow, but rare.
PjPtr projectionOf(PJ_CONTEXT* ctx, const std::string& definition) {
  PjPtr pj(proj_create(ctx, definition.c_str()), proj_destroy);
  if (!pj || !proj_is_crs(pj.get())) return pj;
  pj = projectedPart(ctx, std::move(pj));
  if (!pj) return pj;
  const char* text = proj_as_proj_string(ctx, pj.get(), PJ_PROJ_5, nullptr);
  std::string projection = text ? text : "";
  const std::size_t type = projection.find(" +type=crs");
  if (type != std::string::npos) projection.erase(type, 10);
  if (projection.empty()) return pj;
  PjPtr fast(proj_create(ctx, projection.c_str()), proj_destroy);
  return fast ? std::move(fast) : std::move(pj);
}

ScaleRange scaleRange(const std::string& definition, const std::vector<LonLat>& points) {
  ScaleRange range;
  std::unique_ptr<PJ_CONTEXT, decltype(&proj_context_destroy)> ctx(proj_context_create(), proj_context_destroy);
  proj_log_level(ctx.get(), PJ_LOG_NONE);  // a projection that cannot take a point says so by its errno
  const PjPtr projection = projectionOf(ctx.get(), definition);
  if (!projection || points.empty()) return range;
  for (const LonLat& p : points) {
    proj_errno_reset(projection.get());
    const PJ_FACTORS f = proj_factors(projection.get(), proj_coord(proj_torad(p.lon), proj_torad(p.lat), 0, 0));
    if (proj_errno(projection.get()) != 0 || !std::isfinite(f.meridional_scale) || !std::isfinite(f.parallel_scale)) return range;
    range.low = std::min({range.low, f.meridional_scale, f.parallel_scale});
    range.high = std::max({range.high, f.meridional_scale, f.parallel_scale});
  }
  range.complete = true;
  return range;
}

double errorOf(const ScaleRange& range) {
  if (!range.complete) return std::numeric_limits<double>::quiet_NaN();
  return std::max(std::fabs(range.low - 1), std::fabs(range.high - 1));
}

double wrapLongitude(double lon) { return std::remainder(lon, 360.0); }

struct Candidate {
  std::string kind;
  std::string projection;  // without its scale factor and datum
  std::string scaleKey;    // "+k" or "+k_0"
};

std::vector<Candidate> candidatesAbout(LonLat centre) {
  const std::string lon0 = "+lon_0=" + formatNumber(std::round(wrapLongitude(centre.lon) * 1000) / 1000);
  const std::string lat0 = formatNumber(std::round(centre.lat * 1000) / 1000);
  std::vector<Candidate> out{{"a transverse Mercator", "+proj=tmerc +lat_0=0 " + lon0 + " +x_0=500000 +y_0=0", "+k"},
                             {"a Mercator", "+proj=merc " + lon0 + " +x_0=0 +y_0=0", "+k"}};
  // A cone on the equator is no cone.
  if (std::fabs(centre.lat) >= 1)
    out.push_back({"a Lambert conformal conic", "+proj=lcc +lat_0=" + lat0 + " +lat_1=" + lat0 + " " + lon0 + " +x_0=0 +y_0=0", "+k_0"});
  if (std::fabs(centre.lat) >= 45)
    out.push_back({"a polar stereographic", std::string("+proj=stere +lat_0=") + (centre.lat > 0 ? "90 " : "-90 ") + lon0 + " +x_0=0 +y_0=0", "+k"});
  return out;
}

std::string withScale(const Candidate& c, double k) {
  return c.projection + " " + c.scaleKey + "=" + formatNumber(k) + " +datum=WGS84 +units=m +no_defs";
}

// "-t_srs '+proj=...' (a Mercator fitted to the DEM", for advice to close.
std::string useFitted(const FittedCrs& fitted) {
  return "-t_srs '" + fitted.definition + "' (" + fitted.kind + " fitted to the DEM";
}

}  // namespace

double worstScaleError(const std::string& crsDefinition, const std::vector<LonLat>& points) {
  return errorOf(scaleRange(crsDefinition, points));
}

FittedCrs fittedCrs(const std::vector<LonLat>& points, LonLat centre) {
  FittedCrs best;
  best.error = std::numeric_limits<double>::infinity();
  for (const Candidate& c : candidatesAbout(centre)) {
    const ScaleRange unit = scaleRange(withScale(c, 1), points);
    if (!unit.complete) continue;  // it cannot hold the whole DEM
    // Balanced: the scale factor that makes the largest shrink equal the largest stretch.
    const double k = std::round(2 / (unit.low + unit.high) * 1e6) / 1e6;
    const std::string definition = withScale(c, k);
    const double error = worstScaleError(definition, points);
    if (error < best.error) best = {definition, c.kind, error};  // false for NaN
  }
  return best;
}

std::string percentText(double fraction) {
  const double percent = fraction * 100;
  if (percent >= 1000) return "over 1000 %";  // Web Mercator near a pole: the figure means nothing more
  if (percent >= 10) return formatNumber(std::round(percent)) + " %";
  if (percent < 0.05) return "under 0.1 %";  // not "0 %", which no projection is
  // Two decimals, rounded up, where one would round a figure over 1 % to "1 %".
  const double tenths = std::round(percent * 10) / 10;
  return formatNumber(tenths <= 1 && percent > 1 ? std::ceil(percent * 100) / 100 : tenths) + " %";
}

std::string scaleAdvice(const std::vector<LonLat>& points, LonLat centre, double error) {
  const int utm = utmEpsgFor(centre.lon, centre.lat);
  const double utmError = worstScaleError("EPSG:" + std::to_string(utm), points);
  if (utmError <= 0.01) return "use -t_srs EPSG:" + std::to_string(utm) + " (the UTM zone of the centre)";
  const FittedCrs fitted = fittedCrs(points, centre);
  const std::string use = useFitted(fitted);
  if (fitted.error <= 0.01) return "use " + use + ", within " + percentText(fitted.error) + ")";
  const std::string large = "none of the conformal CRSs tinlod fits keeps a DEM this large within 1 % of true scale";
  // Named only while it is near true scale: a Mercator of a DEM reaching 85 N "within 84 %"
  // would shrink its equator by as much.
  if (fitted.error <= 0.05 && fitted.error < 0.5 * error)
    return large + ": " + use + ") keeps it within " + percentText(fitted.error);
  return large;
}

std::string coverAdvice(const std::vector<LonLat>& points, LonLat centre) {
  const std::string cut = "cut it into regions (gdal_translate -projwin) and run each in a CRS of its own";
  const FittedCrs fitted = fittedCrs(points, centre);
  // At half or one and a half times true scale and beyond (a Mercator reaching a pole), a
  // TIN's slopes and areas mean nothing: no advice.
  if (!(fitted.error < 0.5))
    return "none of the conformal CRSs tinlod fits covers a DEM this large within 50 % of true scale: " + cut;
  return "use " + useFitted(fitted) + ", which covers it, within " +
         percentText(fitted.error) + " of true scale" +
         (fitted.error > 0.01 ? ": slopes, areas and volumes are off by as much)" : ")") +
         (fitted.error > 0.05 ? ", or " + cut : "");
}

}  // namespace tinlod
