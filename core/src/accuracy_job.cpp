// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/accuracy_job.h"

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <charconv>
#include <filesystem>
#include <limits>
#include <functional>
#include <memory>

#include "accuracy_raster_canvas.h"
#include "catalogue_accuracy.h"
#include "catalogue_hierarchy.h"
#include "dataset_files.h"
#include "insertion_levels.h"
#include "layer_crs.h"
#include "tile_catalogue.h"
#include "tinlod/dem_reader.h"
#include "tinlod/error.h"
#include "tinlod/version.h"

namespace tinlod {

void AccuracyOutputs::validate() const {
  options.validate();
  if (!reportPath.empty()) checkAccuracyReportPath(reportPath);
  if (!rasterPath.empty()) checkRasterFormat(raster);
  if (rasterLevel < -1) throw Error("-level must be a level number (0 the original) or -1 for the coarsest");
}

AccuracyFiles stageAccuracyFiles(const AccuracyOutputs& outputs, OutputFiles& files) {
  AccuracyFiles staged;
  if (!outputs.rasterPath.empty()) {
    staged.raster = &files.add(outputs.rasterPath, "-accuracy");  // an input is refused as such first
    // Named as the file is (a link's target), as GDAL names them.
    const std::filesystem::path& raster = staged.raster->target;
    for (const std::string& beside : checkRasterKeepsItsBands(outputs.raster, raster.string()))
      files.checkBeside(*staged.raster, beside);
    // GDAL's statistics of an older raster of that name would be read as the new one's.
    files.checkBeside(*staged.raster, raster.filename().string() + ".aux.xml");
  }
  if (!outputs.reportPath.empty()) staged.report = &files.add(outputs.reportPath, "-report");
  return staged;
}

std::string demName(const std::string& path) { return std::filesystem::path(path).filename().string(); }

std::string crsNameOf(const std::string& wkt) {
  OGRSpatialReference srs;
  if (!wkt.empty() && srs.importFromWkt(wkt.c_str()) == OGRERR_NONE) return crsLabel(srs);
  return "no CRS";
}

LevelAccuracy levelRow(const Hierarchy& h, const std::string& dem, int level, const LevelStats& s) {
  LevelAccuracy row;
  row.dem = dem;
  row.method = h.tinMethod.empty() ? measureName(h.options.measure) : h.tinMethod;
  row.deletePct = h.options.deletePct, row.stopPct = h.options.stopPct;
  row.level = level, row.vertices = s.vertices, row.triangles = s.triangles;
  row.selectSeconds = s.selectSeconds, row.deleteSeconds = s.deleteSeconds, row.certifiedError = s.maxError;
  if (!h.tinMethod.empty()) {  // a single TIN (sample, insert, lod): no levels were made, none of their figures apply
    const double none = std::numeric_limits<double>::quiet_NaN();
    row.deletePct = row.stopPct = row.selectSeconds = row.deleteSeconds = none;
  }
  return row;
}

Error missingLevel(int level, int top) {
  return Error("-level " + std::to_string(level) + " does not exist: the hierarchy has levels 0 to " + std::to_string(top));
}

// A level the file does not have fails before the long work: its levels table says, where
// the level was found missing once the triangles were read (a second for alps_2x2's).
void requireRasterLevel(int level, const std::string& hierarchyPath) {
  if (level < 0) return;
  const int top = static_cast<int>(readHierarchyInfo(hierarchyPath, false).levels.size()) - 1;
  if (top >= 0 && level > top) throw missingLevel(level, top);
}

std::vector<LevelAccuracy> measureLevels(const AccuracyEvaluator& evaluator, const Hierarchy& h, const std::string& dem,
                                         int rasterLevel, const BandStrips* bands, const ProgressRange& progress) {
  const int top = h.coarsest();
  const int chosen = rasterLevel < 0 ? top : rasterLevel;
  if (chosen > top) throw missingLevel(rasterLevel, top);
  std::vector<LevelAccuracy> rows;
  for (int L = 0; L <= top; ++L) {
    LevelAccuracy row = levelRow(h, dem, L, h.levels[L]);
    std::vector<Triangle> triangles;
    for (std::uint32_t t : h.levelTriangles(L)) triangles.push_back(h.triangles[t].v);
    evaluator.evaluate(triangles, row, L == chosen ? bands : nullptr,
                       progress.sub(double(L) / (top + 1), double(L + 1) / (top + 1)));
    rows.push_back(std::move(row));
  }
  return rows;
}

AccuracyReport makeReport(const AccuracyEvaluator& evaluator, const std::string& title, const std::string& crsName,
                          std::vector<LevelAccuracy> rows) {
  return makeReport(evaluator.options(), title, crsName, std::move(rows));
}

AccuracyReport makeReport(const AccuracyOptions& options, const std::string& title, const std::string& crsName,
                          std::vector<LevelAccuracy> rows) {
  AccuracyReport report;
  report.title = title;
  report.reference = referenceName(options.reference);
  report.crsName = crsName;
  report.step = options.step;
  report.controlSpacing = options.controlSpacing;
  report.generator = std::string("tinlod ") + kVersion;
  report.rows = std::move(rows);
  return report;
}

AccuracyReport measureAndWrite(const Dem& dem, const Hierarchy& h, const CrsTransform& toTin, const AccuracyOutputs& outputs,
                               const AccuracyFiles& files, const ProgressRange& progress) {
  const AccuracyEvaluator evaluator(dem, h.base, toTin, outputs.options, progress.sub(0, 0.05));
  // The raster's level goes to disk a strip at a time as it is measured, not held to the end.
  std::unique_ptr<AccuracyRasterCanvas> canvas;
  if (files.raster) canvas = std::make_unique<AccuracyRasterCanvas>(evaluator.grid(), *files.raster, outputs.raster);
  const BandStrips toCanvas = [&canvas](const AccuracyBands& strip, int row0) {
    const Grid& g = strip.elevationDifference;
    canvas->write(strip, TestRect{0, 0, g.cols, g.rows}, 0, row0);
  };
  const double measured = outputs.compareInsert ? 0.5 : 0.9;
  std::vector<LevelAccuracy> rows = measureLevels(evaluator, h, demName(dem.path), outputs.rasterLevel,
                                                  canvas ? &toCanvas : nullptr, progress.sub(0.05, measured));
  requireTestPoints(rows, dem.path);
  if (outputs.compareInsert) {
    const std::vector<std::size_t> counts = insertionCounts(rows);
    if (counts.empty())
      progress.warn("-compare_insert: a single TIN has no level above 0 to compare with greedy insertion: nothing compared");
    else
      progress.inform("Greedy insertion over the same samples to the vertex count of each of " +
                      std::to_string(counts.size()) + " levels");
    compareWithInsertion(rows, measureInsertionLevels(evaluator, dem, h.base, toTin, counts, h.options.stopPct,
                                                      progress.sub(measured, 0.9)));
  }
  AccuracyReport report =
      makeReport(evaluator, std::string(h.tinMethod.empty() ? "Accuracy of the TIN hierarchy of " : "Accuracy of the TIN of ") +
                                demName(dem.path),
                 crsNameOf(evaluator.grid().crsWkt), std::move(rows));
  if (canvas) canvas->finish(progress.sub(0.9, 0.98));
  if (files.report) writeAccuracyReport(report, *files.report);
  return report;
}

namespace {

// The band the TIN was sampled from, as the file records it (1 when it does not).
int sampledBand(const HierarchyInfo& info) {
  const auto item = info.metadata.find("band");
  if (item == info.metadata.end()) return 1;
  const std::string& text = item->second;
  int band = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), band);
  if (error != std::errc() || end != text.data() + text.size() || band < 1)
    throw Error("'" + info.path + "' is damaged: its TINLOD_BAND is '" + text + "', not a band number; give -b");
  return band;
}

// The band to measure: -b, or the one the TIN was sampled from. Another band than that
// measures the TIN against heights it was not made from (488 m of "error" on a DEM whose
// band 2 was sampled, measured against its band 1): said, not refused.
int bandToMeasure(int band, const HierarchyInfo& info, const std::string& named, const AccuracyOutputs& outputs,
                  const ProgressRange& progress) {
  const int sampled = sampledBand(info);
  if (band == 0) return sampled;
  // Against level 0 (-reference tin) the DEM's heights are not the reference: no harm.
  if (band != sampled && outputs.options.reference == Reference::Dem)
    progress.warn("-b " + std::to_string(band) + ": '" + named + "' was sampled from band " + std::to_string(sampled) +
                  " of its DEM, so it is measured against heights it was not made from; leave -b out to measure band " +
                  std::to_string(sampled));
  return band;
}

// The -s_srs the file was sampled with (TINLOD_SOURCE_SRS); empty when it took the DEM's own.
std::string recordedSourceSrs(const HierarchyInfo& info) {
  const auto item = info.metadata.find("source_srs");
  return item == info.metadata.end() || item->second == "from file" ? "" : item->second;
}

// Whether a CRS places a DEM on Earth (not none, nor a local one).
bool placedOnEarth(const std::string& crsWkt) {
  OGRSpatialReference srs;
  return !crsWkt.empty() && srs.importFromWkt(crsWkt.c_str()) == OGRERR_NONE && !srs.IsLocal();
}

// -s_srs when given, else the recorded one for the DEM the build read, or a DEM whose file
// places it nowhere (`demCrsWkt` gives its CRS, read only when needed): read as the build
// read it. Another DEM with a CRS of its own keeps it.
std::string sourceSrsOf(const std::string& given, const HierarchyInfo& info, const std::string& demPath,
                        const std::function<std::string()>& demCrsWkt) {
  if (!given.empty()) return given;
  const std::string recorded = recordedSourceSrs(info);
  if (recorded.empty()) return "";
  const auto source = info.metadata.find("source");
  // An older file's source is as typed, relative to where the build ran.
  const bool same = source != info.metadata.end() && (source->second == demPath || sameFile(source->second, demPath));
  return same || !placedOnEarth(demCrsWkt()) ? recorded : "";
}

// A -s_srs other than the build's reads the DEM elsewhere than the TIN: say so before the
// test points are found off the TIN.
void warnOfAnotherSourceSrs(const std::string& given, const HierarchyInfo& info, const ProgressRange& progress) {
  const std::string recorded = recordedSourceSrs(info);
  if (given.empty() || recorded.empty() || recorded == given) return;
  progress.warn("-s_srs " + given + " is not the " + recorded + " '" + info.path +
                "' was built with: the DEM is read as being elsewhere (leave -s_srs out to take the build's)");
}

// Against level 0 (-reference tin) the test points' heights are the TIN's: which DEM cells
// are valid changes nothing measured (report and raster the same to the bit), and the DEM
// reader's "ignored N cells (treated as nodata)" would say otherwise. Greedy insertion
// (-compare_insert) does read the DEM's valid cells.
std::optional<HeightRange> usedValidRange(const std::optional<HeightRange>& given, const AccuracyOutputs& outputs,
                                          const ProgressRange& progress) {
  if (!given || outputs.options.reference != Reference::Tin || outputs.compareInsert) return given;
  progress.warn("-valid_range is unused with -reference tin: level 0's heights are the reference at every test point, "
                "whichever DEM cells are valid; give -reference dem to measure against the DEM's cells within the range");
  return std::nullopt;
}

}  // namespace

AccuracyReport runAccuracyJob(const std::string& demPath, const std::string& hierarchyPath, const AccuracyOutputs& outputs,
                              int band, const std::string& sourceSrs, const Feedback& feedback,
                              const std::optional<HeightRange>& validHeights) {
  outputs.validate();
  std::vector<std::string> inputs = hierarchyInputs(hierarchyPath);
  inputs.push_back(demPath);
  OutputFiles files(outputs.overwrite, datasetFiles(inputs));
  const AccuracyFiles staged = stageAccuracyFiles(outputs, files);
  const ProgressRange all(feedback, 0, 1);
  if (isCatalogue(hierarchyPath) && !outputs.compareInsert) {
    // A tile at a time: the memory of one tile, whatever the catalogue's size.
    const CatalogueTile tile = readCatalogue(hierarchyPath).front();
    requireTileFile(tile.name, tile.file);  // a tiles folder moved away: say where it must be
    const HierarchyInfo first = readHierarchyInfo(tile.file);
    band = bandToMeasure(band, first, hierarchyPath, outputs, all);  // the catalogue, not its first tile
    warnOfAnotherSourceSrs(sourceSrs, first, all);
    const auto demCrsWkt = [&] {
      return readDemWindow(demPath, band, CellWindow{0, 0, 1, 1}, ProgressRange(Feedback{}, 0, 1)).crsWkt;
    };
    const std::optional<HeightRange> used = usedValidRange(validHeights, outputs, all);
    AccuracyReport report = measureCatalogue(demPath, hierarchyPath, band, used ? *used : recordedRange(first.metadata),
                                             sourceSrsOf(sourceSrs, first, demPath, demCrsWkt), outputs, staged, all);
    files.commit();
    all.finish("Done");
    return report;
  }
  if (!isCatalogue(hierarchyPath)) requireRasterLevel(outputs.rasterLevel, hierarchyPath);
  const StoredHierarchy stored = readHierarchyOrCatalogue(hierarchyPath, all.sub(0, 0.15));
  band = bandToMeasure(band, stored.info, hierarchyPath, outputs, all);
  warnOfAnotherSourceSrs(sourceSrs, stored.info, all);
  // A single TIN is measured against the DEM (below), where the range counts.
  const std::optional<HeightRange> used =
      stored.info.kind == "hierarchy" ? usedValidRange(validHeights, outputs, all) : validHeights;
  // At least this, measured on alps_2x2 (299 MiB with a hierarchy of -block 5), besides the
  // hierarchy: the DEM, the test points and their surfaces.
  const MemoryUse use{"measuring the accuracy against it", 38,
                      "build a tiled hierarchy with tinlod tiles, whose accuracy is measured a tile at a time, or "
                      "measure a part of the DEM (gdal_translate -srcwin)", 0, ""};
  const Dem dem =
      readDem(demPath, band, all.sub(0.15, 0.2), used ? *used : recordedRange(stored.info.metadata), &use);
  const ProgressRange quiet(Feedback{}, 0, 1);  // the sampling run already said what it had to about the CRS
  const CrsTransform toTin =
      CrsTransform::forDem(dem, sourceSrsOf(sourceSrs, stored.info, demPath, [&] { return dem.crsWkt; }),
                           stored.hierarchy.base.crsWkt, quiet);
  AccuracyOutputs chosen = outputs;
  if (stored.info.kind != "hierarchy" && outputs.options.reference == Reference::Tin) {
    // A single TIN against itself says nothing.
    all.inform("'" + hierarchyPath + "' is a single TIN: measured against the DEM (-reference dem)");
    chosen.options.reference = Reference::Dem;
  }
  AccuracyReport report = measureAndWrite(dem, stored.hierarchy, toTin, chosen, staged, all.sub(0.2, 1));
  files.commit();
  all.finish("Done");
  return report;
}

}  // namespace tinlod
