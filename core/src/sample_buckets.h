// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the level-0 samples (deleted vertices) under each triangle of the
// simplification mesh, which certify each level's error. One array ordered by slot,
// rebuilt at each level: the samples under a star are read side by side, where lists
// linked through the vertex array sent each read to a different cache line.
#pragma once

#include <cstdint>
#include <vector>

#include "simplification_mesh.h"
#include "tinlod/importance.h"

namespace tinlod {

class SampleBuckets {
 public:
  // For a run that turns at most `samples` vertices into samples: the arrays then never
  // move as they grow.
  void reset(std::size_t slots, std::size_t samples) {
    start_.assign(slots + 1, 0), points_.clear(), slot_.clear();
    points_.reserve(samples), sparePoints_.reserve(samples), slot_.reserve(samples);
  }

  std::size_t begin(std::int32_t slot) const { return start_[slot]; }
  std::size_t end(std::int32_t slot) const { return start_[slot + 1]; }
  const Point3& point(std::size_t i) const { return points_[i]; }

  // During a level, from any thread (each sample and each new entry has one writer):
  // where a sample goes, and the deleted vertices that become samples.
  void moveTo(std::size_t i, std::int32_t slot) { slot_[i] = slot; }
  void expect(std::size_t added) { added_.resize(added); }
  void add(std::size_t k, const Point3& p, std::int32_t slot) { added_[k] = {p, slot}; }

  // After the mesh is compacted: the samples, old and added, ordered by their new slot.
  void rebuild(const Compaction& slots);

 private:
  struct Added {
    Point3 p;
    std::int32_t slot;
  };
  std::vector<std::uint32_t> start_;  // by slot: its samples are points_[start_[s] .. start_[s + 1])
  std::vector<Point3> points_;
  std::vector<std::int32_t> slot_;    // by sample: its slot once this level's deletions are done
  std::vector<Added> added_;
  std::vector<std::uint32_t> spareStart_, fill_;  // rebuild's, kept from level to level
  std::vector<Point3> sparePoints_;
};

}  // namespace tinlod
