// SPDX-License-Identifier: GPL-3.0-or-later
#include "dataset_files.h"
#include "tinlod/sample_job.h"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "text_and_paths.h"
#include "tin_outline.h"
#include "tinlod/cell_hash.h"
#include "tinlod/crs_transform.h"
#include "tinlod/dem_reader.h"
#include "tinlod/error.h"
#include "tinlod/nodata_filter.h"
#include "tinlod/sampler.h"
#include "tinlod/tile_borders.h"
#include "tinlod/triangulation.h"
#include "tinlod/version.h"

namespace tinlod {
namespace {

// The side (-1, 0 or +1 along rows and along columns) where most of a cell's missing
// 8-neighbours are.
std::pair<int, int> towardsNodata(const Dem& dem, int row, int col) {
  int rows = 0, cols = 0;
  for (int dr = -1; dr <= 1; ++dr)
    for (int dc = -1; dc <= 1; ++dc)
      if ((dr || dc) && !dem.valid(row + dr, col + dc)) rows += dr, cols += dc;
  return {(rows > 0) - (rows < 0), (cols > 0) - (cols < 0)};
}

// The jitter moves each point within its cell, in the DEM's grid (so that the simplifier
// knows where each vertex lies among the cells), by up to `jitter` metres along x and y.
// Cells on the raster's edge move only along it, and its corners not at all: the edge of a
// projected DEM is then a straight line at every level, whose vertices can go without
// changing it.
// An outline cell moves towards the nodata beside it, not away: moved away, its own centre
// would lie in the hole, outside the TIN. A cell on a tile's shared line does not know the
// other tile's cells beside it and moves by the hash alone, as that tile's copy of it does.
struct CellJitter {
  double colPerMetre, rowPerMetre;  // signed: towards +x and +y of the TIN
  int lastRow, lastCol;

  std::pair<double, double> operator()(const Dem& dem, const SampleCell& c, double ux, double uy) const {
    const bool colEdge = c.col == 0 || c.col == lastCol, rowEdge = c.row == 0 || c.row == lastRow;
    double dc = colEdge ? 0 : ux * colPerMetre, dr = rowEdge ? 0 : uy * rowPerMetre;
    if (c.outline && !onSharedLine(dem, c.row, c.col)) {
      const auto [towardsRow, towardsCol] = towardsNodata(dem, c.row, c.col);
      if (towardsCol && !colEdge) dc = towardsCol * ux * std::abs(colPerMetre);
      if (towardsRow && !rowEdge) dr = towardsRow * uy * std::abs(rowPerMetre);
    }
    return {dc, dr};
  }
};

// From the whole raster's middle, so that every tile converts metres to cells alike.
CellJitter cellJitter(const Dem& dem, const CrsTransform& transform, double jitter) {
  const std::array<double, 6>& gt = dem.wholeGeotransform();
  const int width = dem.wholeWidth(), height = dem.wholeHeight();
  const int row = height / 2, col = width / 2 - (width / 2 > 0);
  const auto x = [&](int c) { return gt[0] + (c + 0.5) * gt[1]; };
  const auto y = [&](int r) { return gt[3] + (r + 0.5) * gt[5]; };
  const int prow = row - (row > 0);
  const double across = width > 1 ? transform.groundDistance(x(col), y(row), x(col + 1), y(row)) : 1;
  const double down = height > 1 ? transform.groundDistance(x(width / 2), y(prow), x(width / 2), y(prow + 1)) : 1;
  // +x of the TIN is +col when the geotransform's x step is positive; +y is -row for a
  // north-up DEM (negative y step), +row for a bottom-up one.
  return {jitter / std::max(across, 1e-12) * (gt[1] >= 0 ? 1 : -1), jitter / std::max(down, 1e-12) * (gt[5] < 0 ? -1 : 1),
          dem.height - 1, dem.width - 1};
}

// Each cell's jitter comes from a hash of the seed and the cell's place in the whole
// raster, and its position from the whole raster's geotransform and cell indices: a
// tile's vertex is bit for bit the whole run's (a vertex on a tile's edge moves only along
// it, as one on the raster's edge does).
std::vector<TinVertex> toVertices(const Dem& dem, const std::vector<SampleCell>& cells,
                                  const CrsTransform& transform, double jitter, std::uint64_t seed) {
  const CellJitter move = cellJitter(dem, transform, jitter);
  const std::array<double, 6>& gt = dem.wholeGeotransform();
  std::vector<double> x(cells.size()), y(cells.size());
  std::vector<TinVertex> vertices(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const std::int64_t row = dem.globalRow(cells[i].row), col = dem.globalCol(cells[i].col);
    const double ux = unitFromHash(cellHash(seed, row, col, 1)), uy = unitFromHash(cellHash(seed, row, col, 2));
    const auto [dc, dr] = move(dem, cells[i], ux, uy);
    TinVertex& v = vertices[i];
    v.dcol = static_cast<float>(dc), v.drow = static_cast<float>(dr);
    x[i] = gt[0] + (double(col) + 0.5 + double(v.dcol)) * gt[1];
    y[i] = gt[3] + (double(row) + 0.5 + double(v.drow)) * gt[5];
    v.z = dem.at(cells[i].row, cells[i].col);
    v.row = cells[i].row;
    v.col = cells[i].col;
    v.outline = cells[i].outline;
  }
  transform.apply(x, y);
  for (std::size_t i = 0; i < cells.size(); ++i) vertices[i].x = x[i], vertices[i].y = y[i];
  return vertices;
}

// The distance between two neighbouring cell centres in the TIN's metric CRS.
double cellSizeMetres(const Dem& dem, const CrsTransform& transform) {
  const int row = dem.height / 2, col = std::max(0, dem.width / 2 - 1);
  return transform.groundDistance(dem.centreX(col), dem.centreY(row), dem.centreX(col + 1), dem.centreY(row));
}

// Jitter is meant to break ties, not to move points: beyond a cell it moves them past
// their neighbours and out of the DEM's extent (and a DEM in degrees without a CRS
// has cells of a thousandth of a "metre").
void checkJitter(const Dem& dem, const CrsTransform& transform, double jitter, const ProgressRange& progress) {
  if (dem.width < 2) return;
  const double cell = cellSizeMetres(dem, transform);
  if (jitter >= cell) {
    std::ostringstream msg;
    msg << "-jitter " << jitter << " m is not smaller than the cell size (" << cell << " m): points would leave their cells; ";
    // Cells under a centimetre are degrees read as metres (no CRS, or a local one).
    if (transform.targetWkt().empty() || cell < 0.01)
      msg << "if the DEM is in degrees, name its CRS with -s_srs EPSG:4326 (QGIS: assign the layer's CRS); otherwise ";
    msg << "use e.g. -jitter " << std::setprecision(2) << 0.1 * cell;
    throw Error(msg.str());
  }
  if (jitter > 0.5 * cell) {
    std::ostringstream msg;
    msg << "-jitter " << jitter << " m is more than half the cell size (" << cell
        << " m): a vertex may lie nearer a neighbouring cell's centre than its own, with its own cell's height; "
           "consider a smaller -jitter (e.g. "
        << std::setprecision(2) << 0.1 * cell << ")";
    progress.warn(msg.str());
  }
}

std::map<std::string, std::string> jobMetadata(const std::string& demPath, const SampleOptions& o) {
  return {{"TINLOD_VERSION", kVersion},
          {"TINLOD_KIND", "tin"},
          {"TINLOD_SOURCE", recordedPath(demPath)},
          {"TINLOD_BAND", std::to_string(o.band)},
          {"TINLOD_VALID_RANGE", o.validHeights.text()},
          {"TINLOD_BLOCK", std::to_string(o.block)},
          {"TINLOD_JITTER", formatNumber(o.jitter)},
          {"TINLOD_SEED", std::to_string(o.seed)},
          {"TINLOD_SOURCE_SRS", o.sourceSrs.empty() ? "from file" : o.sourceSrs},
          {"TINLOD_TARGET_SRS", o.targetSrs.empty() ? "auto" : o.targetSrs}};
}

std::string megabytes(double bytes) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(0) << bytes / 1e6 << " MB";
  return s.str();
}

}  // namespace

CrsTransform samplingTransform(const Dem& dem, const SampleOptions& options, const ProgressRange& progress) {
  options.validate();
  CrsTransform transform = CrsTransform::forDem(dem, options.sourceSrs, options.targetSrs, progress);
  checkJitter(dem, transform, options.jitter, progress);
  return transform;
}

Tin sampleTin(const Dem& dem, const SampleOptions& options, const ProgressRange& progress) {
  const CrsTransform transform = samplingTransform(dem, options, progress);
  const std::vector<SampleCell> cells = sampleCells(dem, options.block, options.seed, progress.sub(0, 0.2), options.peaksAndPits);
  Tin tin;
  tin.crsWkt = transform.targetWkt();
  tin.crsName = transform.targetName();
  progress.report(0.2, "Transforming points");
  tin.vertices = toVertices(dem, cells, transform, options.jitter, options.seed);
  const Triangulation triangulation = delaunayTriangles(tin.vertices, progress.sub(0.3, 0.9));
  const std::size_t isolated = keepTrianglesOnValidData(dem, triangulation, tin, progress.sub(0.9, 1));
  if (isolated > 0)
    progress.inform(std::to_string(isolated) + " sampled cells are in no triangle (isolated valid cells, or slivers "
                    "along a straight edge) and were left out");
  if (tin.triangles.empty())
    throw NoTriangle("'" + dem.path + "' gives no triangle: its valid cells are isolated or in a line");
  orderSpatially(tin);
  return tin;
}

SampleSummary summarize(const Tin& tin, std::size_t validCells) {
  SampleSummary s;
  s.validCells = validCells;
  s.vertices = tin.vertices.size();
  s.triangles = tin.triangles.size();
  s.outlineVertices = countOutlineVertices(tin);
  s.area = totalArea(tin);
  s.crsName = tin.crsName;
  return s;
}

SampleSummary runSampleJob(const std::string& demPath, const std::string& outPath,
                           const SampleOptions& options, bool overwrite, const Feedback& feedback,
                           bool vertexIndex) {
  options.validate();
  GpkgWriteOptions writeOptions{overwrite, jobMetadata(demPath, options)};
  writeOptions.vertexIndex = vertexIndex;
  const std::string held = checkOutputPath(outPath, writeOptions);  // fail before the long work, not after it
  OutputFiles files(overwrite, datasetFiles(demPath));
  const StagedFile& out = files.add(outPath, "output", true);
  const ProgressRange all(feedback, 0, 1);
  warnOfReplacedKind(outPath, held, writeOptions, all);
  // Measured on alps_2x2 (250 MiB at -block 3): the DEM, and each sampled vertex.
  const MemoryUse use{"sampling it", 13 + 290.0 / (double(options.block) * options.block),
                      "sample fewer cells with a larger -block, or cut the DEM into parts (gdal_translate -srcwin)", 13,
                      "cut the DEM into parts (gdal_translate -srcwin)"};
  const Dem dem = readDem(demPath, options.band, all.sub(0, 0.1), options.validHeights, &use);
  const Tin tin = sampleTin(dem, options, all.sub(0.1, 0.6));
  writeOptions.metadata["TINLOD_CRS"] = tin.crsName;
  // About 200 bytes a triangle and 150 a vertex in GeoPackage, spatial index included.
  all.inform("Writing " + std::to_string(tin.triangles.size()) + " triangles and " + std::to_string(tin.vertices.size()) +
             " vertices (about " + megabytes(200.0 * tin.triangles.size() + 150.0 * tin.vertices.size()) + ")");
  writeTinGpkg(tin, out, writeOptions, all.sub(0.6, 1));
  files.commit();
  all.finish("Done");
  return summarize(tin, dem.validCount());
}

}  // namespace tinlod
