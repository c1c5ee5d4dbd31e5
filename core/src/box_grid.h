// SPDX-License-Identifier: GPL-3.0-or-later
// Private: boxes (of triangles, of segments) bucketed by a uniform grid.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace tinlod {

struct Box {
  double x0, y0, x1, y1;
};

// A uniform grid of about one bucket per box, buckets square-ish, each listing in
// ascending index the boxes that overlap it: a point's candidates in a few tests whatever
// the number of boxes, and the pairs of boxes that may meet. A degenerate extent (all
// boxes on one vertical or horizontal line) is cut along its one dimension.
class BoxGrid {
 public:
  BoxGrid() = default;
  explicit BoxGrid(const std::vector<Box>& boxes);

  // The boxes of the bucket holding (x, y); none outside the grid (or for NaN).
  std::pair<const std::uint32_t*, const std::uint32_t*> at(double x, double y) const;

  // Each bucket's boxes, as a range [first, last).
  template <class Visit>
  void eachBucket(Visit visit) const {
    for (std::size_t k = 0; k + 1 < start_.size(); ++k) visit(items_.data() + start_[k], items_.data() + start_[k + 1]);
  }

 private:
  // Coordinates inside the grid only: the quotient is then >= 0, so truncation is floor,
  // and it is monotone, so a point inside a box maps inside the box's range of buckets.
  // The clamp takes the far edge into the last bucket.
  int column(double x) const;
  int row(double y) const;
  std::size_t bucket(int c, int r) const { return static_cast<std::size_t>(r) * nx_ + c; }
  template <class Visit>
  void eachBucketOf(const Box& b, Visit visit) const {
    for (int r = row(b.y0); r <= row(b.y1); ++r)
      for (int c = column(b.x0); c <= column(b.x1); ++c) visit(bucket(c, r));
  }

  double x0_ = 0, y0_ = 0, x1_ = -1, y1_ = -1;  // the boxes' extent; empty by default
  double cellW_ = 1, cellH_ = 1;
  int nx_ = 0, ny_ = 0;
  std::vector<std::uint32_t> start_;  // bucket k holds items_[start_[k] .. start_[k + 1])
  std::vector<std::uint32_t> items_;  // indices into the boxes
};

}  // namespace tinlod
