// SPDX-License-Identifier: GPL-3.0-or-later
#include "inserted_vertex_rows.h"

#include <cmath>
#include <utility>

#include "tin_layers.h"

namespace tinlod {

void placeOnMap(const Dem& dem, const CrsTransform& toTin, std::vector<TinVertex>& vertices) {
  std::vector<double> x(vertices.size()), y(vertices.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = dem.centreX(vertices[i].col), y[i] = dem.centreY(vertices[i].row);
  toTin.apply(x, y);
  for (std::size_t i = 0; i < x.size(); ++i) vertices[i].x = x[i], vertices[i].y = y[i];
}

std::vector<ExtraField> InsertedVertexRows::fields() { return {{"insertion", {}, true}, {"error_before", {}, false}}; }

InsertedVertexRows::InsertedVertexRows(const StagedFile& file, const GpkgWriteOptions& options, const Dem& dem,
                                       const CrsTransform& toTin)
    : dem_(dem), toTin_(toTin), writer_([this, file, options] { run(file, options); }) {}

InsertedVertexRows::~InsertedVertexRows() { stop(); }

void InsertedVertexRows::add(const std::vector<InsertedVertex>& inserted) {
  if (inserted.size() <= queued_) return;
  Batch batch{queued_, std::vector<InsertedVertex>(inserted.begin() + std::ptrdiff_t(queued_), inserted.end())};
  queued_ = inserted.size();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (failure_) std::rethrow_exception(failure_);  // at once, not after the whole insertion
    pending_.push_back(std::move(batch));
  }
  wake_.notify_one();
}

void InsertedVertexRows::run(const StagedFile& file, const GpkgWriteOptions& options) {
  try {
    file_.emplace(file, options, toTin_.targetWkt(), fields(), std::vector<ExtraField>{});
    std::vector<Batch> work;
    for (;;) {
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [this] { return stopped_ || done_ || !pending_.empty(); });
        if (stopped_) return;
        std::swap(work, pending_);
        if (work.empty()) break;  // done, and nothing left
      }
      for (const Batch& batch : work) write(batch);
      work.clear();
    }
    file_->vertexRows().finish();
  } catch (...) {
    std::lock_guard<std::mutex> lock(mutex_);
    failure_ = std::current_exception();
  }
}

void InsertedVertexRows::write(const Batch& batch) {
  const std::size_t n = batch.vertices.size();
  std::vector<TinVertex> vertices(n);
  std::vector<ExtraField> extra = fields();
  extra[0].values.resize(n), extra[1].values.resize(n);
  const auto width = std::uint32_t(dem_.width);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t c = batch.vertices[i].candidate;
    vertices[i].z = dem_.z[c];  // at its cell's centre; the outline is set at the end
    vertices[i].row = std::int32_t(c / width), vertices[i].col = std::int32_t(c % width);
    extra[0].values[i] = double(batch.first + i + 1);
    extra[1].values[i] = batch.vertices[i].errorBefore;
  }
  placeOnMap(dem_, toTin_, vertices);
  writeVertexRows(vertices, std::int64_t(batch.first) + 1, file_->vertexRows(), file_->srsId(),
                  extraSetter(extra, int(vertexFields().size())), ProgressRange(Feedback{}, 0, 1));
  for (const TinVertex& v : vertices) places_.push_back({v.x, v.y});
}

std::vector<std::array<double, 2>> InsertedVertexRows::finish() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    done_ = true;
  }
  wake_.notify_one();
  if (writer_.joinable()) writer_.join();
  if (failure_) std::rethrow_exception(failure_);
  written_ = places_.size();
  return std::move(places_);
}

void InsertedVertexRows::stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopped_ = true;
  }
  wake_.notify_one();
  if (writer_.joinable()) writer_.join();
}

void InsertedVertexRows::setOutline(const std::vector<TinVertex>& vertices) {
  SqliteStatement outline = file_->database().prepare("UPDATE vertices SET outline = 1 WHERE fid = ?");
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    if (!vertices[i].outline) continue;
    outline.bind(1, std::int64_t(i) + 1);
    outline.step();
    outline.reset();
  }
}

}  // namespace tinlod
