// SPDX-License-Identifier: GPL-3.0-or-later
#include "sample_buckets.h"

#include "parallel_blocks.h"

namespace tinlod {

// A counting sort by new slot of every sample, the untouched ones included: a slot
// that no deletion touched still moves when the mesh is compacted. The arrays swap with
// the spare ones of the previous level, whose memory is already there.
void SampleBuckets::rebuild(const Compaction& slots) {
  const std::vector<std::int32_t>& oldOf = slots.oldOf;
  const std::vector<std::int32_t>& newOf = slots.newOf;
  std::vector<std::uint32_t>& start = spareStart_;
  start.assign(oldOf.size() + 1, 0);
  for (std::int32_t s : slot_) ++start[newOf[s] + 1];
  for (const Added& a : added_) ++start[newOf[a.slot] + 1];
  for (std::size_t s = 0; s < oldOf.size(); ++s) start[s + 1] += start[s];
  std::vector<Point3>& points = sparePoints_;
  points.clear();  // its old samples are not copied when it grows
  points.resize(start.back());
  std::vector<std::uint32_t>& fill = fill_;
  fill.assign(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < points_.size(); ++i) points[fill[newOf[slot_[i]]]++] = points_[i];
  for (const Added& a : added_) points[fill[newOf[a.slot]]++] = a.p;
  slot_.resize(points.size());
  forEachBlock(static_cast<int>(oldOf.size()), [&](int begin, int end) {
    for (int s = begin; s < end; ++s)
      for (std::uint32_t i = start[s]; i < start[s + 1]; ++i) slot_[i] = s;
  }, {});
  points_.swap(points);
  start_.swap(start);
  added_.clear();
}

}  // namespace tinlod
