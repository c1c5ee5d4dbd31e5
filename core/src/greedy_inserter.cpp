// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/greedy_inserter.h"

#include <CGAL/Convex_hull_traits_adapter_2.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/convex_hull_2.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <queue>

#include "candidate_scanner.h"
#include "tinlod/error.h"

namespace tinlod {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_2;
struct FaceState {
  double error = 0;             // of its worst candidate, as last scanned
  std::uint32_t stamp = 0;      // bumped at each scan: older queue entries are stale
  std::uint32_t candidate = 0;  // its worst candidate
  std::int32_t index = -1;      // its number when the triangulation is handed out
  bool overHole = false;
};
// A vertex knows its place in the insertion order, and its candidate: the scans read it
// where they read the vertex, not from the insertion list (a cache miss a corner).
struct VertexState {
  std::uint32_t order = 0;
  std::uint32_t candidate = 0;
};
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<VertexState, Kernel>;
using FaceBase = CGAL::Triangulation_face_base_with_info_2<FaceState, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;
using FaceHandle = Delaunay::Face_handle;

struct QueueEntry {
  double error;
  std::uint32_t stamp;
  FaceHandle face;
  // The worst error first; equal errors in scan order, so runs are reproducible.
  bool operator<(const QueueEntry& o) const { return error != o.error ? error < o.error : stamp > o.stamp; }
};

}  // namespace

std::array<double, 2> delaunayScales(double width, double height) {
  const double ratio = width / height;
  if (!(ratio > 0) || !std::isfinite(ratio)) return {1, 1};
  std::array<double, 2> best{1, 1};
  double bestError = std::fabs(1 - ratio) / ratio;
  for (int q = 1; q <= 4096 && bestError > 1e-7; ++q) {
    const double p = std::max(1.0, std::round(ratio * q));
    const double error = std::fabs(p / q - ratio) / ratio;
    if (error < bestError - 1e-12) best = {p, double(q)}, bestError = error;
  }
  return best;
}

struct GreedyInserter::Impl {
  InsertGrid grid;
  CandidateScanner scanner;
  Delaunay dt;
  std::priority_queue<QueueEntry> queue;
  // Triangles whose error is at most this are left out of the queue: no run that stops at
  // this tolerance or above would insert their candidate, and at a fine tolerance most
  // rescans end below it (a smaller heap: 10 % of the loop on alps_2x2 at 20 m).
  double floor = 0;
  std::vector<InsertedVertex> inserted;
  std::uint32_t stamp = 0;
  std::vector<FaceHandle> stack;  // flipToDelaunay's, kept from one insertion to the next

  std::array<double, 2> scale;  // whole numbers: see delaunayScales

  explicit Impl(InsertGrid g)
      : grid(std::move(g)), scanner(grid), scale(delaunayScales(grid.cellWidth, grid.cellHeight)) {}

  // Where a candidate is for the Delaunay criterion: the grid scaled to the cells' shape
  // on the ground by whole numbers (delaunayScales).
  Point metric(std::uint32_t id) const {
    return Point(scanner.col(id) * scale[0], scanner.row(id) * scale[1]);
  }

  void scan(FaceHandle f) {
    const ScanResult r =
        scanner.scan({f->vertex(0)->info().candidate, f->vertex(1)->info().candidate, f->vertex(2)->info().candidate});
    f->info() = {r.error, ++stamp, r.candidate, -1, r.overHole};
    if (r.error > floor) queue.push({r.error, stamp, f});
  }

  // A run at a finer tolerance than any before queues the triangles left out until now.
  void lowerFloor(double tolerance) {
    if (tolerance < floor)
      for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f)
        if (f->info().error > tolerance && f->info().error <= floor) queue.push({f->info().error, f->info().stamp, f});
    floor = tolerance;
  }

  // Every triangle above the floor is queued: the queue's top is the largest error unless
  // all are at or below the floor.
  double largestError() {
    dropStale();
    if (!queue.empty() && queue.top().error > floor) return queue.top().error;
    double largest = 0;
    for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) largest = std::max(largest, f->info().error);
    return largest;
  }

  // Drops queue entries of triangles rescanned since.
  void dropStale() {
    while (!queue.empty() && queue.top().face->info().stamp != queue.top().stamp) queue.pop();
  }

  // The new vertex, or null when its position was taken (nothing changed).
  Delaunay::Vertex_handle addVertex(std::uint32_t candidate, double errorBefore, FaceHandle hint) {
    const std::size_t before = dt.number_of_vertices();
    // Split the face (or edge), then flip to Delaunay ourselves: CGAL's own insertion breaks
    // cocircular ties by a symbolic perturbation, the same way everywhere; keeping the new
    // vertex's edges on a tie instead (as delatin does) follows the data, and a grid of
    // cells is cocircular everywhere: 1-2 % fewer vertices at fine tolerances.
    const Delaunay::Vertex_handle v = dt.Triangulation::insert(metric(candidate), hint);
    if (dt.number_of_vertices() == before) return Delaunay::Vertex_handle();
    if (dt.dimension() == 2) flipToDelaunay(v);
    v->info() = {std::uint32_t(inserted.size()), candidate};
    inserted.push_back({candidate, errorBefore});
    return v;
  }

  // Flips each edge opposite the new vertex whose far corner is strictly inside the
  // circle (CGAL's exact predicate, unperturbed), as Lawson's insertion does.
  void flipToDelaunay(Delaunay::Vertex_handle v) {
    stack.clear();
    auto f = dt.incident_faces(v), done = f;
    do stack.push_back(f);
    while (++f != done);
    while (!stack.empty()) {
      const FaceHandle face = stack.back();
      stack.pop_back();
      if (dt.is_infinite(face)) continue;
      const int i = face->index(v);
      const FaceHandle across = face->neighbor(i);
      if (dt.is_infinite(across) || dt.side_of_oriented_circle(across, v->point(), false) != CGAL::ON_POSITIVE_SIDE) continue;
      dt.flip(face, i);  // both faces keep v as a corner
      stack.push_back(face);
      stack.push_back(across);
    }
  }

  // Every triangle an insertion made or changed has the new vertex as a corner (CGAL
  // inserts by splitting a face or edge, then flips, and deletes no face): those alone are
  // rescanned.
  void rescanAround(Delaunay::Vertex_handle v) {
    auto f = dt.incident_faces(v), done = f;
    do {
      if (!dt.is_infinite(f)) scan(f);
    } while (++f != done);
  }

  void startFromHull(const ProgressRange& progress) {
    const std::vector<std::uint32_t> ids = scanner.hullCandidates();
    if (ids.empty()) throw Error("the DEM has no valid cell");
    std::vector<Point> points;
    points.reserve(ids.size());
    for (std::uint32_t id : ids) points.push_back(metric(id));
    std::vector<std::size_t> indices(points.size()), hull;
    for (std::size_t i = 0; i < indices.size(); ++i) indices[i] = i;
    using Traits = CGAL::Convex_hull_traits_adapter_2<Kernel, CGAL::Pointer_property_map<Point>::type>;
    CGAL::convex_hull_2(indices.begin(), indices.end(), std::back_inserter(hull), Traits(CGAL::make_property_map(points)));
    for (std::size_t i : hull) addVertex(ids[i], std::numeric_limits<double>::quiet_NaN(), FaceHandle());
    if (dt.dimension() != 2) throw Error("the valid cells lie in a line: no triangle can be made");
    progress.report(0.5, "Scanning the starting triangles");
    for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) scan(f);
  }

  // The faces in order of the cell blocks their worst candidates lie in (a counting sort),
  // numbered so. CGAL keeps faces in the order it made them, all over the grid, and the
  // vertices in insertion order, all over it too: taken that way every triangle's corners
  // are cache misses for whoever reads them next (the nodata cut, the check, the file's
  // rows, its R-tree). In block order the triangles around a vertex come out close
  // together, and so do the file's rows for one area.
  std::vector<FaceHandle> facesInBlockOrder(const ProgressRange& progress) const {
    constexpr int kBlock = 16;  // cells a side
    const std::size_t blockCols = std::size_t(grid.cols) / kBlock + 1;
    const std::size_t blocks = blockCols * (std::size_t(grid.rows) / kBlock + 1);
    const auto blockOf = [this, blockCols, blocks](const FaceState& s) {
      const double col = std::max(0.0, scanner.col(s.candidate)), row = std::max(0.0, scanner.row(s.candidate));
      return std::min(std::size_t(row / kBlock) * blockCols + std::size_t(col / kBlock), blocks - 1);
    };
    std::vector<std::size_t> start(blocks + 1, 0);
    const double faceCount = double(dt.number_of_faces()) + 1;
    std::size_t seen = 0;
    for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f, ++seen) {
      ++start[blockOf(f->info()) + 1];
      if ((seen & 0xFFFF) == 0) progress.report(0.3 * seen / faceCount, "Collecting the triangles");
    }
    for (std::size_t b = 0; b < blocks; ++b) start[b + 1] += start[b];
    std::vector<FaceHandle> faces(start[blocks]);
    seen = 0;
    for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f, ++seen) {
      if ((seen & 0xFFFF) == 0) progress.report(0.3 + 0.3 * seen / faceCount, "Collecting the triangles");
      const std::size_t at = start[blockOf(f->info())]++;
      f->info().index = std::int32_t(at);
      faces[at] = f;
    }
    return faces;
  }

  bool limitReached(const InsertStop& stop) const {
    if (stop.maxVertices && dt.number_of_vertices() >= stop.maxVertices) return true;
    // An insertion adds at most two triangles.
    return stop.maxTriangles && dt.number_of_faces() + 2 > stop.maxTriangles;
  }
};

GreedyInserter::GreedyInserter(InsertGrid grid, const ProgressRange& progress)
    : impl_(std::make_unique<Impl>(std::move(grid))) {
  impl_->startFromHull(progress);
  progress.report(1, "Scanning the starting triangles");
}

GreedyInserter::~GreedyInserter() = default;

namespace {

// How far along a run is: by the count when one is set, else by the error's fall on a
// log scale from where the run started to the tolerance.
class RunProgress {
 public:
  RunProgress(const InsertStop& stop, std::size_t startVertices, double startError)
      : stop_(stop), startVertices_(startVertices), startError_(startError) {}
  double fraction(std::size_t vertices, std::size_t triangles, double error) {
    double f = 0;
    if (stop_.maxVertices > startVertices_)
      f = std::max(f, double(vertices - startVertices_) / double(stop_.maxVertices - startVertices_));
    if (stop_.maxTriangles) f = std::max(f, double(triangles) / double(stop_.maxTriangles));
    if (stop_.maxError > 0 && std::isfinite(error) && std::isfinite(startError_) && startError_ > stop_.maxError &&
        error > 0)
      f = std::max(f, std::log(startError_ / error) / std::log(startError_ / stop_.maxError));
    done_ = std::clamp(std::max(done_, f), 0.0, 1.0);
    return done_;
  }

 private:
  InsertStop stop_;
  std::size_t startVertices_;
  double startError_;
  double done_ = 0;
};

}  // namespace

void GreedyInserter::run(const InsertStop& stop, const ProgressRange& progress, const std::function<void()>& every) {
  Impl& m = *impl_;
  m.lowerFloor(std::max(0.0, stop.maxError));
  RunProgress fraction(stop, vertexCount(), maxError());
  for (std::size_t step = 0;; ++step) {
    m.dropStale();
    if (m.queue.empty() || m.queue.top().error <= stop.maxError || m.limitReached(stop)) break;
    const QueueEntry top = m.queue.top();
    m.queue.pop();
    const Delaunay::Vertex_handle v = m.addVertex(top.face->info().candidate, top.error, top.face);
    if (v == Delaunay::Vertex_handle()) continue;  // distinct candidates never coincide; never loop on one that did
    m.rescanAround(v);
    if ((step & 1023) != 0) continue;
    if (every) every();
    // CGAL counts the finite triangles by walking the hull: only when a limit needs it.
    progress.report(fraction.fraction(vertexCount(), stop.maxTriangles ? triangleCount() : 0,
                                      m.queue.empty() ? 0 : m.queue.top().error),
                    "Inserting points");
  }
  if (every) every();
}

std::size_t GreedyInserter::vertexCount() const { return impl_->dt.number_of_vertices(); }

std::size_t GreedyInserter::triangleCount() const { return impl_->dt.number_of_faces(); }

double GreedyInserter::maxError() const { return impl_->largestError(); }

const std::vector<InsertedVertex>& GreedyInserter::inserted() const { return impl_->inserted; }

Triangulation GreedyInserter::triangulation(const ProgressRange& progress) const {
  const Delaunay& dt = impl_->dt;
  const std::vector<FaceHandle> faces = impl_->facesInBlockOrder(progress);
  Triangulation out;
  out.triangles.reserve(faces.size());
  out.neighbours.reserve(faces.size());
  for (std::size_t i = 0; i < faces.size(); ++i) {
    if ((i & 0xFFFF) == 0) progress.report(0.6 + 0.4 * i / faces.size(), "Collecting the triangles");
    const FaceHandle& f = faces[i];
    out.triangles.push_back({f->vertex(0)->info().order, f->vertex(1)->info().order, f->vertex(2)->info().order});
    std::array<std::int32_t, 3> n;
    for (int k = 0; k < 3; ++k) n[k] = dt.is_infinite(f->neighbor(k)) ? kNoNeighbour : f->neighbor(k)->info().index;
    out.neighbours.push_back(n);
  }
  return out;
}

double GreedyInserter::candidateCol(std::uint32_t c) const { return impl_->scanner.col(c); }
double GreedyInserter::candidateRow(std::uint32_t c) const { return impl_->scanner.row(c); }

}  // namespace tinlod
