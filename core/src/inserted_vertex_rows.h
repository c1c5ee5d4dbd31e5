// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the vertices layer of a greedy insertion's GeoPackage, written on another core
// while the insertion runs. When every cell is a candidate and none is missing, nothing is
// cut off a hole, so every inserted vertex is a vertex of the TIN, numbered in insertion
// order, and its row can be written as soon as it is inserted; the outline, known only at
// the end, is set then on the few vertices it holds.
#pragma once

#include <array>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "tin_gpkg_file.h"
#include "tinlod/crs_transform.h"
#include "tinlod/dem.h"
#include "tinlod/greedy_inserter.h"

namespace tinlod {

// Vertices at their cells' centres, on the map in the TIN's CRS (x and y set).
void placeOnMap(const Dem& dem, const CrsTransform& toTin, std::vector<TinVertex>& vertices);

class InsertedVertexRows {
 public:
  // The extra vertex fields the rows carry: `insertion` and `error_before`.
  static std::vector<ExtraField> fields();
  // Starts the writer, which makes the file's layers first. `dem` and `toTin` are used by
  // the writer until finish() or stop().
  InsertedVertexRows(const StagedFile& file, const GpkgWriteOptions& options, const Dem& dem, const CrsTransform& toTin);
  ~InsertedVertexRows();
  InsertedVertexRows(const InsertedVertexRows&) = delete;
  InsertedVertexRows& operator=(const InsertedVertexRows&) = delete;

  // From the insertion's thread: queues the vertices inserted since the last call.
  void add(const std::vector<InsertedVertex>& inserted);
  // Waits for the writer; the vertices' places on the map, in insertion order. Rethrows
  // what the writer threw.
  std::vector<std::array<double, 2>> finish();
  // After finish(): how many vertex rows were written.
  std::size_t written() const { return written_; }
  // Stops the writer without finishing (a failure or a cancel elsewhere).
  void stop();
  // After finish(): the file, whose vertex rows are all written but the outline, which
  // this sets, by vertex (insertion order).
  TinGpkgFile& file() { return *file_; }
  void setOutline(const std::vector<TinVertex>& vertices);

 private:
  struct Batch {
    std::size_t first;  // the insertion number of the batch's first vertex, from 0
    std::vector<InsertedVertex> vertices;
  };
  void run(const StagedFile& file, const GpkgWriteOptions& options);
  void write(const Batch& batch);

  const Dem& dem_;
  const CrsTransform& toTin_;
  std::optional<TinGpkgFile> file_;
  std::vector<std::array<double, 2>> places_;
  std::size_t queued_ = 0;  // vertices handed to the writer
  std::size_t written_ = 0;

  std::mutex mutex_;
  std::condition_variable wake_;
  std::vector<Batch> pending_;
  bool done_ = false, stopped_ = false;
  std::exception_ptr failure_;
  std::thread writer_;
};

}  // namespace tinlod
