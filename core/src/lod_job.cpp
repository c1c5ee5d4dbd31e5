// SPDX-License-Identifier: GPL-3.0-or-later
#include "dataset_files.h"
#include "tinlod/lod_job.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>

#include "catalogue_hierarchy.h"
#include "catalogue_lod.h"
#include "extracted_lod.h"
#include "layer_source.h"
#include "layer_transform.h"
#include "number_text.h"
#include "polygon_region.h"
#include "streamed_lod_file.h"
#include "text_and_paths.h"
#include "tile_catalogue.h"
#include "tinlod/error.h"
#include "tinlod/gpkg_writer.h"
#include "tinlod/hierarchy_reader.h"
#include "tinlod/point_reader.h"
#include "tinlod/version.h"

namespace tinlod {
namespace {

// The options as far as they can be checked before reading the hierarchy.
void checkOptions(const LodJobOptions& o) {
  LodOptions lod = o.lod;
  if (!o.centresSrs.empty()) checkSrsText(o.centresSrs, "-center_srs");
  if (!o.centresPath.empty()) {
    checkPointsExist(o.centresPath, "-centers");
    lod.centres.push_back({0, 0});  // stands for the file's points
  }
  if (!o.regionPath.empty()) {
    if (plainPathMissing(parseLayerSource(o.regionPath, "-region").path)) throw Error("-region: '" + o.regionPath + "' does not exist");
    lod.meetsRegion = [](const std::array<std::array<double, 2>, 3>&) { return false; };
  }
  lod.validate();
}

std::map<std::string, std::string> jobMetadata(const std::string& source, const LodJobOptions& o) {
  std::map<std::string, std::string> m{{"TINLOD_VERSION", kVersion}, {"TINLOD_KIND", "lod"}, {"TINLOD_SOURCE", recordedPath(source)}};
  // As given, to the last digit: in degrees (-center_srs) three decimals were 100 m, and a
  // rerun from the recorded centres extracted another TIN.
  std::string centres;
  for (const auto& c : o.lod.centres)
    centres += (centres.empty() ? "" : "; ") + roundTripNumber(c[0]) + " " + roundTripNumber(c[1]);
  if (!centres.empty()) m["TINLOD_CENTERS"] = centres;
  if (!centres.empty() && !o.centresSrs.empty()) m["TINLOD_CENTERS_SRS"] = o.centresSrs;
  if (!o.centresPath.empty()) m["TINLOD_CENTERS_FILE"] = o.centresPath;
  if (!o.regionPath.empty()) m["TINLOD_REGION"] = o.regionPath;
  if (!std::isnan(o.lod.dropoff)) m["TINLOD_DROPOFF"] = formatNumber(o.lod.dropoff);
  if (!std::isnan(o.lod.maxError)) m["TINLOD_MAX_ERROR_LIMIT"] = formatNumber(o.lod.maxError);
  if (o.lod.errorGrowth > 0) m["TINLOD_ERROR_GROWTH"] = formatNumber(o.lod.errorGrowth);
  return m;
}

// The tests with the centres and region read from their files, in the hierarchy's CRS.
LodOptions resolvedOptions(const LodJobOptions& options, const std::string& crsWkt,
                           std::unique_ptr<PolygonRegion>& region, std::vector<std::array<double, 2>>& centres,
                           const ProgressRange& progress) {
  LodOptions lod = options.lod;
  if (!options.centresSrs.empty()) {
    const auto transform = transformToTin(options.centresSrs, crsWkt, "-center_srs", progress);
    for (auto& c : lod.centres)
      if (transform && !transform->Transform(1, &c[0], &c[1]))
        throw Error("-center " + formatNumber(c[0]) + " " + formatNumber(c[1]) + " cannot be transformed from -center_srs to "
                    "the hierarchy's CRS: is it in that CRS's area?");
  }
  if (!options.centresPath.empty())
    for (const auto& p : readPoints(options.centresPath, crsWkt, progress, "-centers")) lod.centres.push_back(p);
  if (!options.regionPath.empty()) {
    region = std::make_unique<PolygonRegion>(options.regionPath, crsWkt, "-region", progress);
    PolygonRegion* meets = region.get();
    lod.meetsRegion = [meets](const std::array<std::array<double, 2>, 3>& t) { return meets->meets(t); };
  }
  centres = lod.centres;
  return lod;
}

// One hierarchy GeoPackage, read whole.
ExtractedLod extractFileLod(const std::string& path, const LodJobOptions& options, std::unique_ptr<PolygonRegion>& region,
                            std::vector<std::array<double, 2>>& centres, const ProgressRange& progress) {
  const StoredHierarchy stored = readHierarchy(path, progress.sub(0, 0.8));
  if (stored.info.kind != "hierarchy")
    throw Error("'" + path + "' is a single TIN (" + stored.info.kind + "), not a hierarchy: make one with tinlod build");
  const Hierarchy& h = stored.hierarchy;
  const LodOptions lod = resolvedOptions(options, h.base.crsWkt, region, centres, progress);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::uint32_t> triangles = extractLod(h, lod, progress.sub(0.8, 1));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ExtractedLod out = extractedLod(h, triangles);
  out.seconds = seconds;
  return out;
}

// What to check when centres lie outside the TIN, by where they came from.
std::string centresAdvice(const LodJobOptions& options) {
  if (!options.lod.centres.empty() && options.centresSrs.empty())
    return "-center is in the hierarchy's CRS; give -center_srs for another (EPSG:4326 for lon/lat)";
  return "are they in the CRS they say (" + std::string(options.lod.centres.empty() ? "-centers' layer" : "-center_srs") +
         ") and on this TIN's data?";
}

// Whole metres for map coordinates: the default six digits printed 5.09405e+06.
std::string coordinate(double v) { return fixedNumber(v, std::fabs(v) >= 1000 ? 0 : 2); }

// A centre far from the data (a longitude and latitude given for a projected TIN, say)
// restores nothing near it: the TIN comes out at its coarsest, which deserves a word.
void warnOfCentresOutside(const std::vector<std::array<double, 2>>& centres, const Envelope& extent,
                          const std::string& crsName, const LodJobOptions& options, const ProgressRange& progress) {
  if (centres.empty() || extent.isEmpty()) return;
  std::size_t outside = 0;
  for (const auto& c : centres) outside += c[0] < extent.minX || c[0] > extent.maxX || c[1] < extent.minY || c[1] > extent.maxY;
  if (outside == 0) return;
  progress.warn(std::to_string(outside) + " of the " + std::to_string(centres.size()) + " centres of detail lie outside the TIN (x " +
                coordinate(extent.minX) + " to " + coordinate(extent.maxX) + ", y " + coordinate(extent.minY) + " to " +
                coordinate(extent.maxY) + " in " + crsName + "): " + centresAdvice(options));
}

// A region that misses the data (another area's polygons, say) restores nothing: as for
// centres, the TIN comes out at its coarsest, which deserves a word.
void warnOfRegionOutside(const PolygonRegion* region, const Envelope& extent, const std::string& crsName,
                         const std::string& regionPath, const ProgressRange& progress) {
  if (!region || extent.isEmpty()) return;
  const std::array<double, 4>& r = region->envelope();
  if (r[2] >= extent.minX && r[0] <= extent.maxX && r[3] >= extent.minY && r[1] <= extent.maxY) return;
  progress.warn("-region: the polygons of '" + regionPath + "' lie outside the TIN (x " + coordinate(extent.minX) + " to " +
                coordinate(extent.maxX) + ", y " + coordinate(extent.minY) + " to " + coordinate(extent.maxY) + " in " +
                crsName + "): nothing is restored for them; are they in the CRS their layer says?");
}

Envelope extentOf(const Tin& tin) {
  Envelope e = Envelope::empty();
  for (const TinVertex& v : tin.vertices) e.extend(v.x, v.y);
  return e;
}

// One hierarchy GeoPackage: read whole, its TIN written whole.
LodSummary writeFileLod(const std::string& path, const StagedFile& out, const LodJobOptions& options,
                        GpkgWriteOptions writeOptions, const ProgressRange& progress) {
  std::unique_ptr<PolygonRegion> region;
  std::vector<std::array<double, 2>> centres;  // in the hierarchy's CRS, once read
  const ExtractedLod lod = extractFileLod(path, options, region, centres, progress.sub(0, 0.6));
  warnOfCentresOutside(centres, extentOf(lod.tin), lod.tin.crsName, options, progress);
  warnOfRegionOutside(region.get(), extentOf(lod.tin), lod.tin.crsName, options.regionPath, progress);
  writeOptions.metadata["TINLOD_CRS"] = lod.tin.crsName;
  writeTinGpkg(lod.tin, out, writeOptions, progress.sub(0.6, 1), {{"level", lod.vertexLevel, true}},
               {{"first_level", lod.firstLevel, true}, {"last_level", lod.lastLevel, true}});
  LodSummary s;
  s.seconds = lod.seconds;
  s.trianglesPerLevel.assign(static_cast<std::size_t>(lod.coarsest) + 1, 0);
  for (double level : lod.firstLevel) ++s.trianglesPerLevel[static_cast<std::size_t>(level)];
  s.vertices = lod.tin.vertices.size(), s.triangles = lod.tin.triangles.size();
  s.levelZeroTriangles = lod.levelZeroTriangles;
  s.crsName = lod.tin.crsName;
  return s;
}

// A catalogue a tile at a time, into the output as each tile's part comes: the memory of
// one tile, and 16 bytes an output triangle for the spatial index.
LodSummary writeCatalogueLod(const std::string& path, const StagedFile& out, const LodJobOptions& options,
                             GpkgWriteOptions writeOptions, const ProgressRange& progress) {
  std::unique_ptr<PolygonRegion> region;
  std::vector<std::array<double, 2>> centres;
  addUnfinishedTiles(path, writeOptions.metadata);
  StreamedLodFile file(out, std::move(writeOptions));
  const CatalogueLodRun run = extractCatalogueLod(
      path, [&](const std::string& crs) { return resolvedOptions(options, crs, region, centres, progress); },
      out.staging.parent_path() / "lod_parts", file, progress.sub(0, 0.95));
  warnOfCentresOutside(centres, file.extent(), file.crsName(), options, progress);
  warnOfRegionOutside(region.get(), file.extent(), file.crsName(), options.regionPath, progress);
  file.finish(progress.sub(0.95, 1));
  LodSummary s;
  s.seconds = run.seconds;
  s.trianglesPerLevel = file.trianglesByFirstLevel();
  s.trianglesPerLevel.resize(std::max(s.trianglesPerLevel.size(), static_cast<std::size_t>(run.coarsest) + 1), 0);
  s.vertices = file.vertices(), s.triangles = file.triangles();
  s.levelZeroTriangles = run.levelZeroTriangles;
  s.crsName = file.crsName();
  return s;
}

}  // namespace

LodSummary runLodJob(const std::string& hierarchyPath, const std::string& outPath, const LodJobOptions& options,
                     bool overwrite, const Feedback& feedback, bool vertexIndex) {
  checkOptions(options);
  GpkgWriteOptions writeOptions{overwrite, jobMetadata(hierarchyPath, options)};
  writeOptions.vertexIndex = vertexIndex;
  std::vector<std::string> inputs = hierarchyInputs(hierarchyPath);
  inputs.insert(inputs.end(), {options.centresPath, options.regionPath});
  OutputFiles files(overwrite, datasetFiles(inputs));
  files.refuseInput(outPath, "output");
  const std::string held = checkOutputPath(outPath, writeOptions);
  const StagedFile& out = files.add(outPath, "output", true);
  const ProgressRange all(feedback, 0, 1);
  warnOfReplacedKind(outPath, held, writeOptions, all);
  if (!options.lod.centres.empty() && std::isnan(options.lod.dropoff) && !(options.lod.errorGrowth > 0))
    all.warn(std::string(options.centresPath.empty() ? "-center" : "-centers") +
             " does nothing without a test that measures from the centres: -dropoff D, or -error_growth G with -max_error");
  const LodSummary s = isCatalogue(hierarchyPath) ? writeCatalogueLod(hierarchyPath, out, options, writeOptions, all)
                                                  : writeFileLod(hierarchyPath, out, options, writeOptions, all);
  files.commit();
  all.finish("Done");
  return s;
}

}  // namespace tinlod
