// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/hierarchy_builder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <queue>

#include "cgal_types.h"
#include "parallel_blocks.h"
#include "tinlod/error.h"

namespace tinlod {
namespace {

using cgal::FaceHandle;
using cgal::FaceTag;
using cgal::VertexHandle;
using Clock = std::chrono::steady_clock;

constexpr std::int32_t kOpenLevel = std::numeric_limits<std::int32_t>::max();
constexpr std::int32_t kNoSample = -1;
constexpr std::size_t kMinLevelShare = 100;  // a level must delete at least 1 / 100 of its vertices

double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

bool containsXY(const cgal::Point& a, const cgal::Point& b, const cgal::Point& c, const cgal::Point& p) {
  const cgal::Traits traits;
  const auto orientation = traits.orientation_2_object();
  return orientation(a, b, p) != CGAL::RIGHT_TURN && orientation(b, c, p) != CGAL::RIGHT_TURN &&
         orientation(c, a, p) != CGAL::RIGHT_TURN;
}

double planeZ(const cgal::Point& a, const cgal::Point& b, const cgal::Point& c, double x, double y) {
  const double d = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
  const double wb = ((x - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (y - a.y())) / d;
  const double wc = ((b.x() - a.x()) * (y - a.y()) - (x - a.x()) * (b.y() - a.y())) / d;
  return a.z() + wb * (b.z() - a.z()) + wc * (c.z() - a.z());
}

// Deletes independent sets of vertices level by level from a CGAL Delaunay
// triangulation of level 0, recording the hierarchy. Faces carry their triangle id;
// faces over holes or outside the data carry kOutside and never change, because only
// vertices whose whole star is data are deleted.
class Simplifier {
 public:
  Simplifier(const Tin& base, std::vector<std::uint8_t> fixed, const HierarchyOptions& options,
             const ProgressRange& progress)
      : options_(options), progress_(progress) {
    h_.base = base;
    h_.options = options;
    h_.fixed = std::move(fixed);
    h_.fixed.resize(base.vertices.size(), 0);
  }

  Hierarchy run(const std::vector<PointXY>& keep) {
    buildTriangulation();
    fixOutline();
    fixNearest(keep);
    const std::size_t original = dt_.number_of_vertices();
    const std::size_t stopCount = static_cast<std::size_t>(std::ceil(options_.stopPct / 100.0 * original));
    h_.levels.push_back({0, original, h_.base.triangles.size(), 0, 0, 0, 0});
    current_ = original;
    triangles_ = h_.base.triangles.size();
    while (current_ > stopCount && (options_.maxLevels == 0 || h_.coarsest() < options_.maxLevels)) {
      const std::int32_t level = h_.coarsest() + 1;
      const Clock::time_point t0 = Clock::now();
      const std::vector<std::pair<double, VertexId>> selected = inMemoryOrder(select(level, stopCount));
      const Clock::time_point t1 = Clock::now();
      // A level that deletes almost nothing only adds a layer: the rest is fixed.
      if (selected.empty() || (!options_.thresholdMode && selected.size() * kMinLevelShare < current_)) break;
      for (std::size_t k = 0; k < selected.size(); ++k) {
        remove(selected[k].second, selected[k].first, level);
        if ((k & 0xFFF) == 0) reportProgress(original, stopCount);
      }
      const Clock::time_point t2 = Clock::now();
      current_ -= selected.size();
      h_.levels.push_back({level, current_, triangles_, selected.size(), seconds(t0, t1), seconds(t1, t2), levelError()});
      reportProgress(original, stopCount);
    }
    finish();
    return std::move(h_);
  }

 private:
  void buildTriangulation() {
    handles_ = cgal::insertVertices(dt_, h_.base.vertices, progress_.sub(0, 0.1));
    for (auto f = dt_.all_faces_begin(); f != dt_.all_faces_end(); ++f) f->info().id = FaceTag::kOutside;
    h_.triangles.reserve(h_.base.triangles.size() * 3);
    for (std::size_t t = 0; t < h_.base.triangles.size(); ++t) {
      const Triangle& tri = h_.base.triangles[t];
      FaceHandle f;
      if (!dt_.is_face(handles_[tri[0]], handles_[tri[1]], handles_[tri[2]], f))
        throw Error("a level-0 triangle is not Delaunay: the TIN was not made by tinlod sample");
      f->info().id = static_cast<std::int32_t>(t);
      HierarchyTriangle ht;
      ht.v = tri;
      ht.lastLevel = kOpenLevel;
      h_.triangles.push_back(ht);
    }
    bucketHead_.assign(h_.triangles.size(), kNoSample);
    bucketNext_.assign(h_.base.vertices.size(), kNoSample);
    h_.vertexLevel.assign(h_.base.vertices.size(), 0);
  }

  // A vertex on the outline or on a hole's edge has a face that is not data: deleting it
  // would change the TIN's extent.
  void fixOutline() {
    for (auto v = dt_.finite_vertices_begin(); v != dt_.finite_vertices_end(); ++v) {
      v->info().fixed = h_.fixed[v->info().id];
      auto f = dt_.incident_faces(v), done = f;
      do {
        if (dt_.is_infinite(f) || f->info().id < 0) {
          h_.fixed[v->info().id] = 1;
          v->info().fixed = true;
          break;
        }
      } while (++f != done);
    }
  }

  // Each point keeps the vertex nearest to it, if it falls on the TIN's data.
  void fixNearest(const std::vector<PointXY>& keep) {
    std::size_t off = 0;
    FaceHandle hint;
    for (const PointXY& p : keep) {
      const cgal::Point q(p[0], p[1], 0);
      const FaceHandle f = dt_.locate(q, hint);
      hint = f;
      if (dt_.is_infinite(f) || f->info().id < 0) {
        ++off;
        continue;
      }
      const VertexHandle v = dt_.nearest_vertex(q, f);
      v->info().fixed = true;
      h_.fixed[v->info().id] = 1;
    }
    if (off > 0)
      progress_.warn(std::to_string(off) + " of the " + std::to_string(keep.size()) +
                     " points to keep fall outside the TIN's data and were ignored");
  }

  bool eligible(VertexHandle v) const {
    if (v->info().fixed) return false;
    return options_.measure != Measure::Degree || static_cast<int>(dt_.degree(v)) <= options_.maxDegree;
  }

  const Star& starOf(VertexHandle v, Star& star) const {
    star.centre = point3(v->point());
    star.ring.clear();
    auto n = dt_.incident_vertices(v), done = n;
    do star.ring.push_back(point3(n->point()));
    while (++n != done);
    return star;
  }

  std::vector<Point3> samplesAround(VertexHandle v) const {
    std::vector<Point3> samples;
    auto f = dt_.incident_faces(v), done = f;
    do
      for (std::int32_t s = bucketHead_[f->info().id]; s != kNoSample; s = bucketNext_[s])
        samples.push_back(point3(h_.base.vertices[s]));
    while (++f != done);
    return samples;
  }

  // Only reads the triangulation and writes the vertex's own tag: safe in parallel.
  void updateImportance(VertexHandle v, Star& scratch) const {
    cgal::VertexTag& tag = v->info();
    const std::vector<Point3> samples = options_.measure == Measure::Error ? samplesAround(v) : std::vector<Point3>();
    tag.importance = importance(options_.measure, starOf(v, scratch), samples);
    tag.stale = false;
  }

  // Importances change only around deleted vertices; those are recomputed at the start of
  // each level, split over the machine's cores (a cancel stops every thread).
  void updateStaleImportances(std::int32_t level) {
    std::vector<VertexHandle> stale;
    for (auto v = dt_.finite_vertices_begin(); v != dt_.finite_vertices_end(); ++v)
      if (v->info().stale && eligible(v)) stale.push_back(v);
    const std::string phase = "Selecting level " + std::to_string(level);
    forEachBlock(static_cast<int>(stale.size()), [&](int begin, int end) {
      Star scratch;
      for (int i = begin; i < end; ++i) updateImportance(stale[i], scratch);
    }, [&](double) { progress_.report(lastFraction_, phase); });
  }

  bool wanted(double importance) const {
    if (options_.measure == Measure::Error && importance > options_.maxError) return false;
    return !options_.thresholdMode || importance < options_.threshold;
  }

  // Best first, ties broken by vertex id: the result never depends on memory layout.
  // Each pick blocks its neighbours, so the set is independent.
  std::vector<std::pair<double, VertexId>> select(std::int32_t level, std::size_t stopCount) {
    updateStaleImportances(level);
    std::vector<std::pair<double, VertexId>> candidates;
    for (auto v = dt_.finite_vertices_begin(); v != dt_.finite_vertices_end(); ++v)
      if (eligible(v) && wanted(v->info().importance)) candidates.emplace_back(v->info().importance, v->info().id);
    std::sort(candidates.begin(), candidates.end());
    std::size_t limit = current_ - stopCount;
    if (!options_.thresholdMode)
      limit = std::min(limit, static_cast<std::size_t>(std::floor(options_.deletePct / 100.0 * current_)));
    std::vector<std::pair<double, VertexId>> selected;
    for (const auto& [imp, id] : candidates) {
      if (selected.size() >= limit) break;
      const VertexHandle v = handles_[id];
      if (v->info().stamp == level) continue;
      selected.emplace_back(imp, id);
      v->info().stamp = level;
      auto n = dt_.incident_vertices(v), done = n;
      do n->info().stamp = level;
      while (++n != done);
    }
    return selected;
  }

  // Removing in the spatial order of insertion rather than best-first keeps CGAL's faces
  // and vertices in cache: about 15 % off the delete step on alps_2x2.
  std::vector<std::pair<double, VertexId>> inMemoryOrder(std::vector<std::pair<double, VertexId>> selected) const {
    std::sort(selected.begin(), selected.end(), [&](const auto& a, const auto& b) {
      return handles_[a.second]->info().rank < handles_[b.second]->info().rank;
    });
    return selected;
  }

  void remove(VertexId id, double importance, std::int32_t level) {
    const VertexHandle v = handles_[id];
    const std::int32_t g = static_cast<std::int32_t>(h_.groups.size());
    Group group;
    group.vertex = id;
    group.level = level;
    group.importance = importance;

    // One walk around the star: its faces become the accept triangles, the vertex
    // counter-clockwise after v in each face is the next ring vertex, and the faces'
    // samples and the vertex itself go to the reject triangles.
    std::vector<VertexHandle>& ring = ring_;
    ring.clear();
    std::vector<std::int32_t>& samples = samples_;
    samples.assign(1, static_cast<std::int32_t>(id));
    group.acceptBegin = static_cast<std::uint32_t>(h_.links.size());
    auto f = dt_.incident_faces(v), fdone = f;
    do {
      ring.push_back(f->vertex(dt_.ccw(f->index(v))));
      const std::int32_t t = f->info().id;
      h_.links.push_back(static_cast<std::uint32_t>(t));
      h_.triangles[t].lastLevel = level - 1;
      h_.triangles[t].replacedBy = g;
      for (std::int32_t s = bucketHead_[t]; s != kNoSample; s = bucketNext_[s]) samples.push_back(s);
      f->info().id = FaceTag::kDying;  // CGAL may reuse a star face for a new one
    } while (++f != fdone);
    group.acceptEnd = static_cast<std::uint32_t>(h_.links.size());
    group.ringBegin = static_cast<std::uint32_t>(h_.rings.size());
    for (VertexHandle u : ring) h_.rings.push_back(u->info().id);
    group.ringEnd = static_cast<std::uint32_t>(h_.rings.size());

    dt_.remove(v);
    handles_[id] = VertexHandle();
    h_.vertexLevel[id] = level - 1;

    group.rejectBegin = static_cast<std::uint32_t>(h_.links.size());
    const std::vector<FaceHandle>& created = numberNewFaces(ring.front(), level, g);
    group.rejectEnd = static_cast<std::uint32_t>(h_.links.size());
    if (created.size() + 2 != ring.size())
      throw Error("internal error: deleting a vertex of degree " + std::to_string(ring.size()) + " made " +
                  std::to_string(created.size()) + " triangles");
    group.error = redistribute(samples, created);
    for (FaceHandle f : created) errorHeap_.push({h_.triangles[f->info().id].error, f->info().id});
    for (VertexHandle u : ring) u->info().stale = true;
    h_.groups.push_back(group);
    triangles_ -= 2;
  }

  static bool isNew(FaceHandle f) { return f->info().id == FaceTag::kFresh || f->info().id == FaceTag::kDying; }

  // The faces that filled the hole are connected and each touches the ring: find one
  // around a ring vertex, then walk across edges to the others.
  const std::vector<FaceHandle>& numberNewFaces(VertexHandle ringVertex, std::int32_t level, std::int32_t g) {
    std::vector<FaceHandle>& created = created_;
    created.clear();
    auto f = dt_.incident_faces(ringVertex), done = f;
    do
      if (isNew(f)) {
        number(f, level, g);
        break;
      }
    while (++f != done);
    for (std::size_t k = 0; k < created.size(); ++k)
      for (int i = 0; i < 3; ++i) {
        const FaceHandle n = created[k]->neighbor(i);
        if (isNew(n)) number(n, level, g);
      }
    return created;
  }

  void number(FaceHandle f, std::int32_t level, std::int32_t g) {
    const std::int32_t t = static_cast<std::int32_t>(h_.triangles.size());
    f->info().id = t;
    HierarchyTriangle ht;
    ht.v = {f->vertex(0)->info().id, f->vertex(1)->info().id, f->vertex(2)->info().id};
    ht.firstLevel = level;
    ht.lastLevel = kOpenLevel;
    ht.group = g;
    h_.triangles.push_back(ht);
    bucketHead_.push_back(kNoSample);
    h_.links.push_back(static_cast<std::uint32_t>(t));
    created_.push_back(f);
  }

  // Puts each sample in the new triangle that holds it, and measures its vertical
  // distance there: the certified error of the level, whatever the measure.
  double redistribute(const std::vector<std::int32_t>& samples, const std::vector<FaceHandle>& created) {
    double worst = 0;
    for (std::int32_t s : samples) {
      const TinVertex& sv = h_.base.vertices[s];
      const cgal::Point p(sv.x, sv.y, sv.z);
      FaceHandle home;
      for (FaceHandle f : created)
        if (containsXY(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point(), p)) {
          home = f;
          break;
        }
      if (home == FaceHandle()) throw Error("internal error: a sample left its star");
      const std::int32_t t = home->info().id;
      bucketNext_[s] = bucketHead_[t];
      bucketHead_[t] = s;
      const double e = std::fabs(sv.z - planeZ(home->vertex(0)->point(), home->vertex(1)->point(),
                                               home->vertex(2)->point(), sv.x, sv.y));
      h_.triangles[t].error = std::max(h_.triangles[t].error, e);
      worst = std::max(worst, e);
    }
    return worst;
  }

  // The largest error of the current triangles: a max-heap of every triangle made, whose
  // top is dropped while it belongs to a replaced triangle.
  double levelError() {
    while (!errorHeap_.empty() && h_.triangles[errorHeap_.top().second].lastLevel != kOpenLevel) errorHeap_.pop();
    return errorHeap_.empty() ? 0.0 : errorHeap_.top().first;
  }

  void reportProgress(std::size_t original, std::size_t stopCount) {
    const double span = std::max<double>(1.0, double(original) - double(stopCount));
    lastFraction_ = std::clamp(0.1 + 0.9 * (double(original) - double(current_)) / span, 0.1, 1.0);
    progress_.report(lastFraction_, "Simplifying level " + std::to_string(h_.coarsest() + 1));
  }

  void finish() {
    const std::int32_t top = h_.coarsest();
    for (HierarchyTriangle& t : h_.triangles)
      if (t.lastLevel == kOpenLevel) t.lastLevel = top;
    for (auto v = dt_.finite_vertices_begin(); v != dt_.finite_vertices_end(); ++v) h_.vertexLevel[v->info().id] = top;
  }

  static Point3 point3(const cgal::Point& p) { return {p.x(), p.y(), p.z()}; }
  static Point3 point3(const TinVertex& v) { return {v.x, v.y, v.z}; }

  const HierarchyOptions& options_;
  ProgressRange progress_;
  Hierarchy h_;
  cgal::Delaunay dt_;
  std::vector<VertexHandle> handles_;         // by vertex id; null once deleted
  std::vector<std::int32_t> bucketHead_;      // by triangle id: first deleted sample under it
  std::vector<std::int32_t> bucketNext_;      // by vertex id: next sample in the same bucket
  std::priority_queue<std::pair<double, std::int32_t>> errorHeap_;  // (error, triangle id)
  std::vector<VertexHandle> ring_;            // scratch buffers, reused to spare allocations
  std::vector<std::int32_t> samples_;
  std::vector<FaceHandle> created_;
  std::size_t current_ = 0, triangles_ = 0;
  double lastFraction_ = 0.1;
};

}  // namespace

Hierarchy buildHierarchy(const Tin& base, std::vector<std::uint8_t> fixed, const HierarchyOptions& options,
                         const ProgressRange& progress, const std::vector<PointXY>& keep) {
  options.validate();
  return Simplifier(base, std::move(fixed), options, progress).run(keep);
}

}  // namespace tinlod
