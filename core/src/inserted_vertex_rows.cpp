// SPDX-License-Identifier: GPL-3.0-or-later
#include "inserted_vertex_rows.h"

#include <cmath>
#include <utility>

#include "tin_layers.h"

namespace tinlod {

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
  std::vector<double> x(n), y(n);
  std::vector<std::uint32_t> row(n), col(n);
  const auto width = std::uint32_t(dem_.width);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t c = batch.vertices[i].candidate;
    row[i] = c / width, col[i] = c % width;
    x[i] = dem_.centreX(int(col[i])), y[i] = dem_.centreY(int(row[i]));
  }
  toTin_.apply(x, y);
  GpkgFeatureRows& rows = file_->vertexRows();
  GpkgGeometryBlob point(file_->srsId());
  const int extra = int(vertexFields().size());
  for (std::size_t i = 0; i < n; ++i) {
    const auto id = std::int64_t(batch.first + i) + 1;
    rows.set(0, id);
    rows.set(1, row[i]);
    rows.set(2, col[i]);
    rows.set(3, 0);  // the outline is set at the end
    rows.set(extra, id);
    rows.setReal(extra + 1, batch.vertices[i].errorBefore);  // NaN for the starting hull: null
    point.pointZ(x[i], y[i], dem_.z[batch.vertices[i].candidate]);
    rows.insert(id, point);
    places_.push_back({x[i], y[i]});
  }
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
