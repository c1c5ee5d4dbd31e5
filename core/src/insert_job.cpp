// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/insert_job.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <future>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <utility>

#include "dataset_files.h"
#include "grid_bend.h"
#include "inserted_vertex_rows.h"
#include "parallel_blocks.h"
#include "text_and_paths.h"
#include "tinlod/accuracy_statistics.h"
#include "tinlod/dem_reader.h"
#include "tinlod/error.h"
#include "tinlod/gpkg_writer.h"
#include "tinlod/nodata_filter.h"
#include "tinlod/sample_job.h"
#include "tinlod/tin_rasterizer.h"
#include "tinlod/version.h"

namespace tinlod {
namespace {

// Makes the writer of the vertex rows once the TIN's CRS is known (the caller owns it).
using VertexRowsStart = std::function<InsertedVertexRows*(const CrsTransform&)>;

InsertedTin insertedTinWith(const Dem& dem, const InsertOptions& options, const ProgressRange& progress,
                            const VertexRowsStart& startRows);

// Metres between neighbouring cell centres at the DEM's centre, along a row and a column.
std::array<double, 2> cellSizeMetres(const Dem& dem, const CrsTransform& toTin) {
  const int row = std::max(0, dem.height / 2 - 1), col = std::max(0, dem.width / 2 - 1);
  const double x = dem.centreX(col), y = dem.centreY(row);
  return {toTin.groundDistance(x, y, dem.centreX(col + 1), y), toTin.groundDistance(x, y, x, dem.centreY(row + 1))};
}

// Where the sampled TIN's (jittered) vertices are, in DEM cell units.
std::vector<CandidatePoint> samplePositions(const Dem& dem, const CrsTransform& toTin, const Tin& sampled) {
  std::vector<double> x(sampled.vertices.size()), y(sampled.vertices.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = sampled.vertices[i].x, y[i] = sampled.vertices[i].y;
  toTin.applyInverse(x, y);
  const auto& gt = dem.geotransform;
  std::vector<CandidatePoint> points(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const TinVertex& v = sampled.vertices[i];
    points[i] = {(x[i] - gt[0]) / gt[1] - 0.5, (y[i] - gt[3]) / gt[5] - 0.5, float(v.z), v.row, v.col};
  }
  return points;
}

// Counter-clockwise on the map, whichever way the DEM's rows run.
void orientTriangles(Tin& tin) {
  for (Triangle& t : tin.triangles)
    if (triangleArea(tin, t) < 0) std::swap(t[1], t[2]);
}

// Vertices on an edge that only one triangle has (the hull and the holes' edges): CGAL's
// neighbour k is across the edge opposite corner k.
void markOutline(Tin& tin, const std::vector<std::array<std::int32_t, 3>>& neighbours) {
  for (std::size_t t = 0; t < tin.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (neighbours[t][k] == kNoNeighbour)
        tin.vertices[tin.triangles[t][(k + 1) % 3]].outline = tin.vertices[tin.triangles[t][(k + 2) % 3]].outline = true;
}

void warnIfHolesOpen(const InsertSummary& s, const ProgressRange& progress) {
  if (s.holesOpen)
    progress.warn("the vertex or triangle limit came before the TIN was cut free of the nodata holes: " +
                  std::to_string(s.uncoveredCells) + " valid cells are not covered; raise the limit");
}

}  // namespace

InsertSummary measureInsertedTin(const Dem& dem, const InsertedTin& out, const ProgressRange& progress) {
  InsertSummary s = out.summary;
  std::vector<double> z(out.tin.vertices.size());
  for (std::size_t i = 0; i < z.size(); ++i) z[i] = out.tin.vertices[i].z;
  const Grid heights = rasterizeTin(out.cellPositions, z, out.tin.triangles, dem.width, dem.height, progress);
  ErrorStatistics errors;
  for (int r = 0; r < dem.height; ++r)
    for (int c = 0; c < dem.width; ++c) {
      if (!dem.valid(r, c)) continue;
      if (std::isnan(heights.at(c, r)))
        ++s.uncoveredCells;
      else
        errors.add(heights.at(c, r) - dem.at(r, c), c, r, std::uint64_t(r) * dem.width + c);
    }
  s.measuredCells = errors.count();
  s.measuredMaxError = s.measuredCells ? errors.maxAbs() : 0;
  s.rmse = s.measuredCells ? errors.rmse() : 0;
  return s;
}

InsertGrid makeInsertGrid(const Dem& dem, const CrsTransform& toTin, const Tin* sampled, bool onGrid) {
  InsertGrid grid;
  grid.cols = dem.width, grid.rows = dem.height, grid.z = dem.z.data();
  if (dem.width > 1 && dem.height > 1 && !onGrid) {
    const std::array<double, 2> size = cellSizeMetres(dem, toTin);
    grid.cellWidth = size[0], grid.cellHeight = size[1];
  }
  if (sampled) grid.samples = samplePositions(dem, toTin, *sampled);
  return grid;
}

InsertedTin greedyInsertionTin(const Dem& dem, const InsertOptions& options, const ProgressRange& progress) {
  InsertedTin out = insertedTin(dem, options, progress.sub(0, 0.9));
  out.summary = measureInsertedTin(dem, out, progress.sub(0.9, 1));
  warnIfHolesOpen(out.summary, progress);
  return out;
}

InsertedTin insertedTin(const Dem& dem, const InsertOptions& options, const ProgressRange& progress) {
  return insertedTinWith(dem, options, progress, {});
}

namespace {

// The writer stops before what it reads (the transform, a local) goes, whatever ends the run.
struct StopRowsOnExit {
  InsertedVertexRows* rows;
  ~StopRowsOnExit() {
    if (rows) rows->stop();
  }
};

InsertedTin insertedTinWith(const Dem& dem, const InsertOptions& options, const ProgressRange& progress,
                            const VertexRowsStart& startRows) {
  options.validate();
  const bool cells = options.candidates == InsertCandidates::Cells;
  // With sampled candidates the sampling says what it has to about the CRS, once.
  const CrsTransform toTin = CrsTransform::forDem(dem, options.sample.sourceSrs, options.sample.targetSrs,
                                                  cells ? progress : ProgressRange(Feedback{}, 0, 1));
  Tin sampled;
  if (options.candidates == InsertCandidates::Samples) sampled = sampleTin(dem, options.sample, progress.sub(0, 0.1));
  InsertedTin out;
  out.summary.candidates = cells ? dem.validCount() : sampled.vertices.size();

  const auto start = std::chrono::steady_clock::now();
  GreedyInserter inserter(makeInsertGrid(dem, toTin, cells ? nullptr : &sampled, options.delaunayOnGrid),
                          progress.sub(0.1, 0.15));
  if (options.maxVertices && options.maxVertices < inserter.vertexCount())
    progress.warn("-max_vertices " + std::to_string(options.maxVertices) + " is less than the " +
                  std::to_string(inserter.vertexCount()) + " corners of the valid area's hull, where every run starts");
  if (options.maxTriangles && options.maxTriangles < inserter.triangleCount())
    progress.warn("-max_triangles " + std::to_string(options.maxTriangles) + " is less than the " +
                  std::to_string(inserter.triangleCount()) + " triangles of the valid area's hull, where every run starts");
  InsertedVertexRows* rows = startRows ? startRows(toTin) : nullptr;
  const StopRowsOnExit stopRows{rows};
  std::function<void()> handRows;
  if (rows) handRows = [rows, &inserter] { rows->add(inserter.inserted()); };
  inserter.run({options.maxError, options.maxVertices, options.maxTriangles}, progress.sub(0.15, 0.95), handRows);
  out.summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.summary.maxError = inserter.maxError();
  out.summary.holesOpen = std::isinf(out.summary.maxError);

  // Every inserted vertex as a TIN vertex: its cell and height now, its place on the map
  // (PROJ: 0.3 s a half million) from the rows' writer, which had it, or on the other core
  // while the triangles are taken out of the triangulation, which reads only the cells.
  const std::vector<std::array<double, 2>> places = rows ? rows->finish() : std::vector<std::array<double, 2>>{};
  const std::vector<InsertedVertex>& inserted = inserter.inserted();
  if (rows && places.size() != inserted.size()) throw Error("internal error: the vertex rows' writer missed vertices");
  Tin all;
  all.vertices.reserve(inserted.size());
  for (const InsertedVertex& iv : inserted) {
    const std::uint32_t c = iv.candidate;
    if (cells)
      all.vertices.push_back({0, 0, dem.z[c], std::int32_t(c / dem.width), std::int32_t(c % dem.width), false});
    else
      all.vertices.push_back(sampled.vertices[c]);  // already on the map
  }
  std::future<void> placed;
  if (rows)
    for (std::size_t i = 0; i < places.size(); ++i) all.vertices[i].x = places[i][0], all.vertices[i].y = places[i][1];
  else if (cells)
    placed = std::async(std::launch::async, [&dem, &toTin, &all] { placeOnMap(dem, toTin, all.vertices); });
  // The triangles tinlod sample would keep: none over a hole, no sliver the jitter of
  // sampled candidates leaves along a straight edge.
  std::vector<std::array<std::int32_t, 3>> neighbours;
  all.triangles =
      trianglesOnValidData(dem, inserter.triangulation(progress.sub(0.95, 0.97)), all, &neighbours, progress.sub(0.97, 1));
  if (placed.valid()) placed.get();
  // As tinlod sample says it: a file of no triangle and "Maximum error 0 m" was a success.
  if (all.triangles.empty())
    throw NoTriangle("'" + dem.path + "' gives no triangle: its valid cells are isolated or in a line");
  // Keep the vertices some triangle uses, in insertion order.
  for (VertexId i : dropUnusedVertices(all)) {
    out.cellPositions.push_back({inserter.candidateCol(inserted[i].candidate), inserter.candidateRow(inserted[i].candidate)});
    out.insertion.push_back(std::uint32_t(i + 1));
    out.errorBefore.push_back(inserted[i].errorBefore);
  }
  out.tin = std::move(all);
  for (TinVertex& v : out.tin.vertices) v.outline = false;  // set anew from the kept triangles
  out.tin.crsWkt = toTin.targetWkt();
  out.tin.crsName = toTin.targetName();
  markOutline(out.tin, neighbours);
  orientTriangles(out.tin);
  const TriangleAt triangle = [&out](std::size_t i) -> const Triangle& { return out.tin.triangles[i]; };
  const std::size_t count = out.tin.triangles.size();
  checkGridBend(dem, toTin, out.tin.vertices, count, triangle, count, triangle, out.summary.maxError, "the TIN", progress);

  InsertSummary& s = out.summary;
  s.vertices = out.tin.vertices.size(), s.triangles = out.tin.triangles.size(), s.crsName = out.tin.crsName;
  return out;
}

std::map<std::string, std::string> jobMetadata(const std::string& demPath, const InsertOptions& o, const std::string& crsName) {
  std::map<std::string, std::string> items{{"TINLOD_VERSION", kVersion},
                                           {"TINLOD_KIND", "tin"},
                                           {"TINLOD_METHOD", "insert"},
                                           {"TINLOD_SOURCE", recordedPath(demPath)},
                                           {"TINLOD_BAND", std::to_string(o.sample.band)},
                                           {"TINLOD_VALID_RANGE", o.sample.validHeights.text()},
                                           {"TINLOD_CANDIDATES", candidatesName(o.candidates)},
                                           {"TINLOD_MAX_ERROR_LIMIT", formatNumber(o.maxError)},
                                           {"TINLOD_MAX_VERTICES_LIMIT", std::to_string(o.maxVertices)},
                                           {"TINLOD_MAX_TRIANGLES_LIMIT", std::to_string(o.maxTriangles)},
                                           {"TINLOD_DELAUNAY", o.delaunayOnGrid ? "grid" : "ground"},
                                           {"TINLOD_SOURCE_SRS", o.sample.sourceSrs.empty() ? "from file" : o.sample.sourceSrs},
                                           {"TINLOD_TARGET_SRS", o.sample.targetSrs.empty() ? "auto" : o.sample.targetSrs},
                                           {"TINLOD_CRS", crsName}};
  if (o.candidates == InsertCandidates::Samples) {
    items["TINLOD_BLOCK"] = std::to_string(o.sample.block);
    items["TINLOD_JITTER"] = formatNumber(o.sample.jitter);
    items["TINLOD_SEED"] = std::to_string(o.sample.seed);
  }
  return items;
}

// What is known only once the insertion has run and been checked: the file's last
// metadata items.
struct LateFigures {
  double maxError = std::numeric_limits<double>::quiet_NaN();
  std::shared_future<InsertSummary> check;
  // Called while the file waits for the check: a stop asked then is heard (it throws).
  std::function<void()> whileWaiting;
};

std::map<std::string, std::string> lateMetadata(const LateFigures& late) {
  while (late.check.wait_for(std::chrono::milliseconds(100)) != std::future_status::ready)
    if (late.whileWaiting) late.whileWaiting();
  const InsertSummary s = late.check.get();
  std::map<std::string, std::string> items{{"TINLOD_UNCOVERED_CELLS", std::to_string(s.uncoveredCells)},
                                           {"TINLOD_MEASURED_MAX_ERROR", formatNumber(s.measuredMaxError)},
                                           {"TINLOD_RMSE", formatNumber(s.rmse)}};
  // Not while a count stopped the run before the holes were cut out: no maximum then.
  if (std::isfinite(late.maxError)) items["TINLOD_MAX_ERROR"] = formatNumber(late.maxError);
  return items;
}

// Every inserted vertex is a vertex of the TIN, in insertion order, when every cell is a
// candidate and none is missing: no triangle is cut off a hole. Its row can then be
// written while the insertion runs.
bool rowsAsInserted(const Dem& dem, const InsertOptions& options) {
  return options.candidates == InsertCandidates::Cells && dem.validCount() == dem.z.size();
}

// The rest of a file whose vertex rows were written while the insertion ran.
void finishFile(InsertedVertexRows& rows, const InsertedTin& result, const std::vector<ExtraField>& extra,
                const ProgressRange& progress) {
  TinGpkgFile& file = rows.file();
  if (rows.written() != result.tin.vertices.size()) {
    // Some vertex was dropped after all: the rows are written again, numbered as kept.
    file.clearVertexRows();
    writeVertices(result.tin, file.vertexRows(), file.srsId(), extraSetter(extra, int(vertexFields().size())),
                  progress.sub(0, 0.2));
  } else {
    rows.setOutline(result.tin.vertices);
  }
  file.indexLater(result.tin);
  file.finish(result.tin, {}, progress.sub(0.2, 0.8), progress.sub(0.8, 1));
}

}  // namespace

InsertSummary runInsertJob(const std::string& demPath, const std::string& outPath, const InsertOptions& options,
                           bool overwrite, const Feedback& feedback, bool vertexIndex) {
  options.validate();
  GpkgWriteOptions writeOptions{overwrite, {{"TINLOD_KIND", "tin"}}};  // the kind: refuse another's file now
  writeOptions.vertexIndex = vertexIndex;
  const std::string held = checkOutputPath(outPath, writeOptions);  // fail before the long work, not after it
  OutputFiles files(overwrite, datasetFiles(demPath));
  const StagedFile& out = files.add(outPath, "output", true);
  const ProgressRange all(feedback, 0, 1);
  warnOfReplacedKind(outPath, held, writeOptions, all);
  // At least this, measured on alps_2x2 keeping 0.6 % of its cells (317 MiB); more as the
  // insertion keeps more (851 MiB at 8 %).
  const MemoryUse use{"greedy insertion", 56,
                      "cut the DEM into parts (gdal_translate -srcwin), or build a tiled hierarchy with tinlod tiles", 0, ""};
  const Dem dem = readDem(demPath, options.sample.band, all.sub(0, 0.1), options.sample.validHeights, &use);
  const auto late = std::make_shared<LateFigures>();
  writeOptions.lateMetadata = [late] { return lateMetadata(*late); };
  // The vertex rows are written on the other core while the insertion runs on this one,
  // when they can be (0.4 s of an alps_2x2 insert at 20 m).
  std::unique_ptr<InsertedVertexRows> vertexRows;
  VertexRowsStart startRows;
  if (rowsAsInserted(dem, options))
    startRows = [&](const CrsTransform& toTin) {
      writeOptions.metadata = jobMetadata(demPath, options, toTin.targetName());
      vertexRows = std::make_unique<InsertedVertexRows>(out, writeOptions, dem, toTin);
      return vertexRows.get();
    };
  const InsertedTin result = insertedTinWith(dem, options, all.sub(0.1, 0.85), startRows);
  late->maxError = result.summary.maxError;
  // The independent check runs while the file is written; its figures are the file's last
  // metadata items. (It reports no progress from its thread: the file's thread does while it
  // waits for them.) It takes one core when the writing would outlast it (about 1.5 us a
  // triangle against 0.1 us a cell), else all.
  const bool longWrite = result.tin.triangles.size() * 16 > std::size_t(dem.width) * dem.height;
  // Given up with the file (a stop, a failed write), the check stops too: waiting for it
  // held a stop asked while the triangles were written by up to 1.5 s (alps_2x2 at 10 m).
  const auto abandonCheck = std::make_shared<std::atomic<bool>>(false);
  Feedback checkFeedback;
  checkFeedback.progress = [abandonCheck](double, const std::string&) { return !abandonCheck->load(); };
  late->whileWaiting = [all] { all.report(0.99, "Checking every cell against the TIN"); };
  late->check = std::async(std::launch::async, [&dem, &result, longWrite, checkFeedback] {
    std::optional<ThisThreadAlone> alone;
    if (longWrite) alone.emplace();
    return measureInsertedTin(dem, result, ProgressRange(checkFeedback, 0, 1));
  }).share();
  if (!vertexRows) writeOptions.metadata = jobMetadata(demPath, options, result.summary.crsName);
  std::vector<ExtraField> extra = InsertedVertexRows::fields();
  extra[0].values.assign(result.insertion.begin(), result.insertion.end());
  extra[1].values = result.errorBefore;
  try {
    if (vertexRows)
      finishFile(*vertexRows, result, extra, all.sub(0.85, 1));
    else
      writeTinGpkg(result.tin, out, writeOptions, all.sub(0.85, 1), extra);
  } catch (...) {
    // The file's R-tree packing and the check read `result` and `dem`: they end before
    // those go (the file's threads with it).
    abandonCheck->store(true);
    vertexRows.reset();
    late->check.wait();
    throw;
  }
  vertexRows.reset();
  const InsertSummary summary = late->check.get();
  warnIfHolesOpen(summary, all);
  files.commit();
  all.finish("Done");
  return summary;
}

}  // namespace tinlod
