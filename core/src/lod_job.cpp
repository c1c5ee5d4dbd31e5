// SPDX-License-Identifier: GPL-3.0-or-later
#include "dataset_files.h"
#include "tinlod/lod_job.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>

#include "catalogue_hierarchy.h"
#include "layer_source.h"
#include "polygon_region.h"
#include "text_and_paths.h"
#include "tinlod/error.h"
#include "tinlod/gpkg_writer.h"
#include "tinlod/point_reader.h"
#include "tinlod/version.h"

namespace tinlod {
namespace {

// The options as far as they can be checked before reading the hierarchy.
void checkOptions(const LodJobOptions& o) {
  LodOptions lod = o.lod;
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

// The extracted triangles as a TIN of the vertices they use, in hierarchy order.
Tin extractedTin(const Hierarchy& h, const std::vector<std::uint32_t>& triangles, std::vector<double>& vertexLevel) {
  Tin tin;
  tin.crsWkt = h.base.crsWkt, tin.crsName = h.base.crsName;
  tin.vertices = h.base.vertices;
  for (std::uint32_t t : triangles) tin.triangles.push_back(h.triangles[t].v);
  for (VertexId v : dropUnusedVertices(tin)) vertexLevel.push_back(h.vertexLevel[v]);
  return tin;
}

std::map<std::string, std::string> jobMetadata(const std::string& source, const LodJobOptions& o) {
  std::map<std::string, std::string> m{{"TINLOD_VERSION", kVersion}, {"TINLOD_KIND", "lod"}, {"TINLOD_SOURCE", source}};
  std::string centres;
  char text[64];
  for (const auto& c : o.lod.centres) {
    std::snprintf(text, sizeof text, "%.3f %.3f", c[0], c[1]);  // map coordinates to the millimetre
    centres += (centres.empty() ? "" : "; ") + std::string(text);
  }
  if (!centres.empty()) m["TINLOD_CENTERS"] = centres;
  if (!o.centresPath.empty()) m["TINLOD_CENTERS_FILE"] = o.centresPath;
  if (!o.regionPath.empty()) m["TINLOD_REGION"] = o.regionPath;
  if (!std::isnan(o.lod.dropoff)) m["TINLOD_DROPOFF"] = formatNumber(o.lod.dropoff);
  if (!std::isnan(o.lod.maxError)) m["TINLOD_MAX_ERROR_LIMIT"] = formatNumber(o.lod.maxError);
  if (o.lod.errorGrowth > 0) m["TINLOD_ERROR_GROWTH"] = formatNumber(o.lod.errorGrowth);
  return m;
}

}  // namespace

LodSummary runLodJob(const std::string& hierarchyPath, const std::string& outPath, const LodJobOptions& options,
                     bool overwrite, const Feedback& feedback, bool vertexIndex) {
  checkOptions(options);
  GpkgWriteOptions writeOptions{overwrite, jobMetadata(hierarchyPath, options)};
  writeOptions.vertexIndex = vertexIndex;
  checkOutputPath(outPath, writeOptions);
  std::vector<std::string> inputs = hierarchyInputs(hierarchyPath);
  inputs.insert(inputs.end(), {options.centresPath, options.regionPath});
  OutputFiles files(overwrite, datasetFiles(inputs));
  const StagedFile& out = files.add(outPath, "output", true);
  const ProgressRange all(feedback, 0, 1);
  const StoredHierarchy stored = readHierarchyOrCatalogue(hierarchyPath, all.sub(0, 0.5));
  if (stored.info.kind != "hierarchy")
    throw Error("'" + hierarchyPath + "' is a single TIN (" + stored.info.kind + "), not a hierarchy: make one with tinlod build");
  const Hierarchy& h = stored.hierarchy;
  LodOptions lod = options.lod;
  if (!options.centresPath.empty())
    for (const auto& p : readPoints(options.centresPath, h.base.crsWkt, all, "-centers")) lod.centres.push_back(p);
  std::unique_ptr<PolygonRegion> region;
  if (!options.regionPath.empty()) {
    region = std::make_unique<PolygonRegion>(options.regionPath, h.base.crsWkt, "-region", all);
    lod.meetsRegion = [&region](const std::array<std::array<double, 2>, 3>& t) { return region->meets(t); };
  }
  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::uint32_t> triangles = extractLod(h, lod, all.sub(0.5, 0.6));
  LodSummary s;
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::vector<double> vertexLevel;
  const Tin tin = extractedTin(h, triangles, vertexLevel);
  std::vector<ExtraField> triangleFields{{"first_level", {}, true}, {"last_level", {}, true}};
  s.trianglesPerLevel.assign(static_cast<std::size_t>(h.coarsest()) + 1, 0);
  for (std::uint32_t t : triangles) {
    triangleFields[0].values.push_back(h.triangles[t].firstLevel);
    triangleFields[1].values.push_back(h.triangles[t].lastLevel);
    ++s.trianglesPerLevel[static_cast<std::size_t>(h.triangles[t].firstLevel)];
  }
  writeOptions.metadata["TINLOD_CRS"] = h.base.crsName;
  writeTinGpkg(tin, out, writeOptions, all.sub(0.6, 1), {{"level", vertexLevel, true}}, triangleFields);
  files.commit();
  all.finish("Done");
  s.vertices = tin.vertices.size(), s.triangles = tin.triangles.size();
  s.levelZeroTriangles = h.levels.empty() ? 0 : h.levels[0].triangles;
  s.crsName = h.base.crsName;
  return s;
}

}  // namespace tinlod
