// SPDX-License-Identifier: GPL-3.0-or-later
#include "dataset_files.h"
#include "tinlod/line_layers.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>

#include "layer_crs.h"
#include "gdal_handles.h"
#include "gpkg_output.h"
#include "layer_source.h"
#include "text_and_paths.h"
#include "tinlod/crs_transform.h"
#include "tinlod/error.h"
#include "tinlod/version.h"

namespace tinlod {
namespace {

// M for an endpoint: GeoPackage readers do not all take infinity.
constexpr double kEndpointM = 1e300;

// What reading left out: a NaN or infinite vertex would collapse a line's Douglas-Peucker
// values (every distance to it is NaN), so it goes, and a line it leaves too short goes too.
struct LeftOut {
  std::size_t vertices = 0, lines = 0;
  std::size_t features = 0;  // that gave no line at all: their ids have no row in the outputs
  std::string otherType;  // a geometry that is no line, as GDAL names it
};

void addLine(const OGRLineString& l, long long fid, LineSet& out, LeftOut& left) {
  Polyline line;
  for (int i = 0; i < l.getNumPoints(); ++i) {
    if (std::isfinite(l.getX(i)) && std::isfinite(l.getY(i)))
      line.push_back({l.getX(i), l.getY(i)});
    else
      ++left.vertices;
  }
  if (line.size() >= 2)
    out.lines.push_back(std::move(line)), out.feature.push_back(fid);
  else if (static_cast<int>(line.size()) < l.getNumPoints())
    ++left.lines;
}

void addParts(const OGRGeometry* g, long long fid, LineSet& out, LeftOut& left) {
  if (!g) return;
  switch (wkbFlatten(g->getGeometryType())) {
    case wkbLineString:
      addLine(*g->toLineString(), fid, out, left);
      break;
    case wkbMultiLineString:
      for (const OGRLineString* part : *g->toMultiLineString()) addParts(part, fid, out, left);
      break;
    case wkbGeometryCollection:
      for (const OGRGeometry* part : *g->toGeometryCollection()) addParts(part, fid, out, left);
      break;
    default:
      // Curves (circular strings, compound curves, multicurves) as the lines GDAL makes of them.
      if (OGR_GT_IsCurve(g->getGeometryType()) || OGR_GT_IsSubClassOf(g->getGeometryType(), wkbMultiCurve)) {
        std::unique_ptr<OGRGeometry> linear(g->getLinearGeometry());
        if (linear && wkbFlatten(linear->getGeometryType()) != wkbFlatten(g->getGeometryType())) addParts(linear.get(), fid, out, left);
      } else if (left.otherType.empty()) {
        left.otherType = OGRGeometryTypeToName(g->getGeometryType());
      }
      break;
  }
}

// A layer declared as points or polygons would give no line: refused by its type, before
// its features are read. Layers of mixed or unknown type are judged by what they hold.
void checkLineLayer(OGRLayer& layer, const std::string& path) {
  const OGRwkbGeometryType type = layer.GetGeomType();
  const OGRwkbGeometryType flat = wkbFlatten(type);
  const bool lines = flat == wkbUnknown || flat == wkbGeometryCollection || OGR_GT_IsCurve(type) ||
                     OGR_GT_IsSubClassOf(type, wkbMultiCurve);
  if (lines) return;
  const std::string holds = flat == wkbNone ? "no geometries" : OGRGeometryTypeToName(type) + std::string(" geometries");
  throw Error("LINES: '" + path + "' holds " + holds + " (layer '" + layer.GetName() + "'): a line layer is needed");
}

void warnLeftOut(const LeftOut& left, const std::string& path, const ProgressRange& progress) {
  if (left.features > 0)
    progress.warn(std::to_string(left.features) + (left.features == 1 ? " feature" : " features") + " of '" + path +
                  "' gave no line (no geometry, an empty one, fewer than 2 points, or no line in it): left out");
  if (left.vertices == 0) return;
  std::string message = "skipped " + std::to_string(left.vertices) + (left.vertices == 1 ? " vertex" : " vertices") +
                        " with coordinates that are not finite numbers (NaN or infinity) in '" + path + "'";
  if (left.lines > 0)
    message += ", and skipped " + std::to_string(left.lines) + (left.lines == 1 ? " line" : " lines") +
               " this left with fewer than 2 vertices";
  progress.warn(message);
}

// The centre of the lines, in their own CRS; longitudes spanning more than half the globe
// are taken as crossing the antimeridian.
std::array<double, 2> centreOf(const LineSet& set, bool geographic) {
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const Polyline& line : set.lines)
    for (const LinePoint& p : line) x0 = std::min(x0, p[0]), x1 = std::max(x1, p[0]), y0 = std::min(y0, p[1]), y1 = std::max(y1, p[1]);
  if (!geographic || x1 - x0 <= 180) return {(x0 + x1) / 2, (y0 + y1) / 2};
  double e0 = 1e300, e1 = -1e300;  // eastern longitudes, 0 to 360
  for (const Polyline& line : set.lines)
    for (const LinePoint& p : line) {
      const double east = p[0] < 0 ? p[0] + 360 : p[0];
      e0 = std::min(e0, east), e1 = std::max(e1, east);
    }
  const double lon = (e0 + e1) / 2;
  return {lon > 180 ? lon - 360 : lon, (y0 + y1) / 2};
}

// The layer's CRS when metric, else the UTM zone of its centre.
std::unique_ptr<OGRCoordinateTransformation> toMetric(const OGRSpatialReference* src, LineSet& out,
                                                      const ProgressRange& progress) {
  if (!src) {
    progress.warn("the lines have no CRS: their coordinates are taken as metres");
    out.crsName = "no CRS";
    return nullptr;
  }
  OGRSpatialReference source(*src);
  source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (source.IsProjected() && std::fabs(source.GetLinearUnits() - 1) < 1e-9) {
    out.crsWkt = wkt2(source);
    out.crsName = source.GetName() ? source.GetName() : "";
    return nullptr;
  }
  OGRSpatialReference wgs84;
  wgs84.SetWellKnownGeogCS("WGS84");
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  const std::array<double, 2> centre = centreOf(out, source.IsGeographic());
  double lon = centre[0], lat = centre[1];
  std::unique_ptr<OGRCoordinateTransformation> toGeo(OGRCreateCoordinateTransformation(&source, &wgs84));
  if (!toGeo || !toGeo->Transform(1, &lon, &lat)) throw Error("the lines' CRS cannot be transformed to WGS 84");
  OGRSpatialReference utm;
  utm.importFromEPSG(utmEpsgFor(lon, lat));
  utm.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  out.crsWkt = wkt2(utm);
  out.crsName = utm.GetName() ? utm.GetName() : "UTM";
  progress.inform("the lines are not in metres: measured in " + out.crsName);
  return std::unique_ptr<OGRCoordinateTransformation>(OGRCreateCoordinateTransformation(&source, &utm));
}

}  // namespace

LineSet readLines(const std::string& path, const ProgressRange& progress) {
  const OpenLayer open = openLayer(path, "LINES");
  OGRLayer& layer = *open.layer;
  checkLineLayer(layer, path);
  LineSet out;
  LeftOut left;
  for (auto& f : layer) {
    const std::size_t before = out.lines.size();
    addParts(f->GetGeometryRef(), f->GetFID(), out, left);
    left.features += out.lines.size() == before;
  }
  warnLeftOut(left, path, progress);
  if (out.lines.empty())
    throw Error("LINES: the layer of '" + path + "' has no lines (a line layer is needed)" +
                (left.otherType.empty() ? std::string() : ": its features are " + left.otherType));
  const auto transform = toMetric(layerCrs(layer), out, progress);
  if (transform)
    for (Polyline& line : out.lines)
      for (LinePoint& p : line)
        if (!transform->Transform(1, &p[0], &p[1])) throw Error("a point of the lines cannot be transformed to " + out.crsName);
  return out;
}

namespace {

void setOrNull(OGRFeature& f, const char* field, double value) {
  if (std::isnan(value))
    f.SetFieldNull(f.GetFieldIndex(field));
  else
    f.SetField(field, value);
}

// A line of `feature` with the fields already set on `f`.
void writeLineFeature(OGRLayer& layer, OGRFeature& f, const Polyline& points, long long feature) {
  auto* line = new OGRLineString();
  for (const LinePoint& p : points) line->addPoint(p[0], p[1]);
  f.SetFID(OGRNullFID);
  f.SetField("feature", static_cast<GIntBig>(feature));
  f.SetGeometryDirectly(line);
  writeFeature(layer, f);
}

// Vertex i of line l (numbered from 1) with the fields already set on `f`.
void writeVertexFeature(OGRLayer& layer, OGRFeature& f, const LinePoint& p, std::size_t l, std::size_t i) {
  f.SetFID(OGRNullFID);
  f.SetField("line", static_cast<GIntBig>(l) + 1);
  f.SetField("vertex", static_cast<GIntBig>(i));
  f.SetGeometryDirectly(new OGRPoint(p[0], p[1]));
  writeFeature(layer, f);
}

void writeLines(OGRLayer& layer, const LineSet& set, const std::vector<std::vector<double>>& values) {
  OGRFeature f(layer.GetLayerDefn());
  for (std::size_t l = 0; l < set.lines.size(); ++l) {
    auto* line = new OGRLineString();
    for (std::size_t i = 0; i < set.lines[l].size(); ++i)
      line->addPointM(set.lines[l][i][0], set.lines[l][i][1], std::isinf(values[l][i]) ? kEndpointM : values[l][i]);
    f.SetFID(OGRNullFID);
    f.SetField("feature", static_cast<GIntBig>(set.feature[l]));
    f.SetGeometryDirectly(line);
    writeFeature(layer, f);
  }
}

void writeVertices(OGRLayer& layer, const LineSet& set, const std::vector<std::vector<double>>& values) {
  OGRFeature f(layer.GetLayerDefn());
  for (std::size_t l = 0; l < set.lines.size(); ++l)
    for (std::size_t i = 0; i < set.lines[l].size(); ++i) {
      setOrNull(f, "value", std::isinf(values[l][i]) ? std::numeric_limits<double>::quiet_NaN() : values[l][i]);
      writeVertexFeature(layer, f, set.lines[l][i], l, i);
    }
}

void writeSimplified(OGRLayer& layer, const LineSet& set, const std::vector<Polyline>& lines) {
  OGRFeature f(layer.GetLayerDefn());
  for (std::size_t l = 0; l < lines.size(); ++l) writeLineFeature(layer, f, lines[l], set.feature[l]);
}

bool isDpLayer(const std::string& name) { return name == "lines" || name == "vertices" || name == "simplified"; }
bool isConcavityLayer(const std::string& name) { return name == "vertices" || name == "parts"; }

double lengthOf(const Polyline& line) {
  double length = 0;
  for (std::size_t i = 1; i < line.size(); ++i) length += std::hypot(line[i][0] - line[i - 1][0], line[i][1] - line[i - 1][1]);
  return length;
}


}  // namespace

void DpOptions::validate() const {
  if (!std::isnan(threshold) && !(threshold >= 0 && std::isfinite(threshold)))
    throw Error("-threshold must be 0 or more metres (got " + formatNumber(threshold) +
                "): the simplified lines keep the vertices whose value exceeds it");
}

DpSummary runDpJob(const std::string& inPath, const std::string& outPath, const DpOptions& options, bool overwrite,
                   const Feedback& feedback) {
  options.validate();
  GpkgWriteOptions writeOptions{overwrite, {{"TINLOD_VERSION", kVersion}, {"TINLOD_KIND", "dp_values"}, {"TINLOD_SOURCE", recordedPath(inPath)}}};
  checkOutputPath(outPath, writeOptions);
  OutputFiles files(overwrite, datasetFiles(inPath));
  const StagedFile& staged = files.add(outPath, "output", true);
  const ProgressRange all(feedback, 0, 1);
  const LineSet set = readLines(inPath, all.sub(0, 0.2));
  DpSummary s;
  s.lines = set.lines.size(), s.crsName = set.crsName;
  std::vector<std::vector<double>> values;
  std::vector<Polyline> simple;
  for (const Polyline& line : set.lines) {
    values.push_back(douglasPeuckerValues(line));
    s.vertices += line.size();
    if (options.threshold >= 0) {
      simple.push_back(simplified(line, values.back(), options.threshold));
      s.keptVertices += simple.back().size();
    }
  }
  all.report(0.5, "Douglas-Peucker values");
  if (options.threshold >= 0) {
    s.crossings = crossingCount(simple);
    writeOptions.metadata["TINLOD_THRESHOLD"] = formatNumber(options.threshold);
    writeOptions.metadata["TINLOD_CROSSINGS"] = std::to_string(s.crossings);
  }
  GpkgOutput out(staged, writeOptions, isDpLayer);
  OGRLayer* lines = out.createLayer("lines", wkbLineStringM, set.crsWkt, {{"feature"}});
  OGRLayer* vertices = options.points ? out.createLayer("vertices", wkbPoint, set.crsWkt, {{"line"}, {"vertex"}, {"value", OFTReal}}) : nullptr;
  OGRLayer* simplifiedLayer = options.threshold >= 0 ? out.createLayer("simplified", wkbLineString, set.crsWkt, {{"feature"}}) : nullptr;
  out.begin();
  writeLines(*lines, set, values);
  if (vertices) writeVertices(*vertices, set, values);
  if (simplifiedLayer) writeSimplified(*simplifiedLayer, set, simple);
  out.commit();
  out.finish(all.sub(0.6, 1));
  files.commit();
  all.finish("Done");
  return s;
}

void ConcavityOptions::validate() const {
  // A negative window is named as such before a missing one is asked for.
  if (window < 0 || windowFraction < 0 || !std::isfinite(window))
    throw Error("-window and -window_fraction must be more than 0 (got " + formatNumber(window < 0 ? window : windowFraction) + ")");
  if (!(window > 0) && !(windowFraction > 0))
    throw Error("give the window: -window d (metres along the line) or -window_fraction f (of each line's length)");
  if (window > 0 && windowFraction > 0) throw Error("give -window or -window_fraction, not both");
  if (windowFraction >= 0.5) throw Error("-window_fraction must be below 0.5: the window reaches both ways");
  if (radius < 0 || !std::isfinite(radius)) throw Error("-radius must be 0 (the window) or more metres");
  if (!(threshold >= 0)) throw Error("-threshold must be 0 or more");
}

ConcavitySummary runConcavityJob(const std::string& inPath, const std::string& outPath, const ConcavityOptions& options,
                                 bool overwrite, const Feedback& feedback) {
  options.validate();
  GpkgWriteOptions writeOptions{overwrite, {{"TINLOD_VERSION", kVersion}, {"TINLOD_KIND", "concavity"}, {"TINLOD_SOURCE", recordedPath(inPath)}}};
  checkOutputPath(outPath, writeOptions);
  OutputFiles files(overwrite, datasetFiles(inPath));
  const StagedFile& staged = files.add(outPath, "output", true);
  const ProgressRange all(feedback, 0, 1);
  const LineSet set = readLines(inPath, all.sub(0, 0.2));
  ConcavitySummary s;
  s.lines = set.lines.size(), s.crsName = set.crsName;
  GpkgOutput out(staged, writeOptions, isConcavityLayer);
  OGRLayer* vertices = out.createLayer("vertices", wkbPoint, set.crsWkt, {{"line"}, {"vertex"}, {"secant", OFTReal}, {"disk", OFTReal}});
  OGRLayer* parts = out.createLayer("parts", wkbLineString, set.crsWkt, {{"feature"}, {"class", OFTString}});
  out.begin();
  OGRFeature v(vertices->GetLayerDefn()), p(parts->GetLayerDefn());
  std::size_t totalVertices = 0;
  for (const Polyline& line : set.lines) totalVertices += line.size();
  for (std::size_t l = 0; l < set.lines.size(); ++l) {
    const Polyline& line = set.lines[l];
    const double window = options.window > 0 ? options.window : options.windowFraction * lengthOf(line);
    const std::vector<double> secant = secantConcavity(line, window);
    const std::vector<double> disk = diskConcavity(line, options.radius > 0 ? options.radius : window);
    for (std::size_t i = 0; i < line.size(); ++i, ++s.vertices) {
      setOrNull(v, "secant", secant[i]);
      setOrNull(v, "disk", disk[i]);
      writeVertexFeature(*vertices, v, line[i], l, i);
    }
    for (const LinePart& part : curvatureParts(line, secant, options.threshold)) {
      ++(part.curvature == Curvature::Convex ? s.convex : part.curvature == Curvature::Concave ? s.concave : s.straight);
      p.SetField("class", curvatureName(part.curvature).c_str());
      writeLineFeature(*parts, p, part.line, set.feature[l]);
    }
    // By vertices: a few long contours may hold most of them.
    all.report(0.2 + 0.5 * double(s.vertices) / std::max<std::size_t>(totalVertices, 1), "Concavity");
  }
  all.report(0.7, "Writing the GeoPackage");
  out.commit();
  out.finish(all.sub(0.7, 1));
  files.commit();
  all.finish("Done");
  return s;
}

}  // namespace tinlod
