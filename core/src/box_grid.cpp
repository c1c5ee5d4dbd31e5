// SPDX-License-Identifier: GPL-3.0-or-later
#include "box_grid.h"

#include <algorithm>
#include <cmath>

namespace tinlod {

// Two passes over the boxes (count, then fill) build the buckets as one flat array.
BoxGrid::BoxGrid(const std::vector<Box>& boxes) {
  if (boxes.empty()) return;
  x0_ = y0_ = INFINITY;
  x1_ = y1_ = -INFINITY;
  for (const Box& b : boxes) {
    x0_ = std::min(x0_, b.x0), y0_ = std::min(y0_, b.y0);
    x1_ = std::max(x1_, b.x1), y1_ = std::max(y1_, b.y1);
  }
  const double w = x1_ - x0_, h = y1_ - y0_;
  const double n = static_cast<double>(boxes.size());
  // On a degenerate extent the buckets line up along its one dimension.
  nx_ = h > 0 ? (w > 0 ? static_cast<int>(std::clamp(std::round(std::sqrt(n * w / h)), 1.0, n)) : 1) : static_cast<int>(n);
  ny_ = static_cast<int>(std::clamp(std::ceil(n / nx_), 1.0, n));
  cellW_ = w > 0 ? w / nx_ : 1;
  cellH_ = h > 0 ? h / ny_ : 1;
  start_.assign(bucket(0, ny_) + 1, 0);
  for (const Box& b : boxes) eachBucketOf(b, [this](std::size_t k) { ++start_[k + 1]; });
  for (std::size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
  items_.resize(start_.back());
  std::vector<std::uint32_t> next(start_.begin(), start_.end() - 1);
  for (std::uint32_t i = 0; i < boxes.size(); ++i) eachBucketOf(boxes[i], [&](std::size_t k) { items_[next[k]++] = i; });
}

int BoxGrid::column(double x) const { return std::min(static_cast<int>((x - x0_) / cellW_), nx_ - 1); }
int BoxGrid::row(double y) const { return std::min(static_cast<int>((y - y0_) / cellH_), ny_ - 1); }

std::pair<const std::uint32_t*, const std::uint32_t*> BoxGrid::at(double x, double y) const {
  if (!(x >= x0_ && x <= x1_ && y >= y0_ && y <= y1_)) return {nullptr, nullptr};  // false for NaN too
  const std::size_t k = bucket(column(x), row(y));
  return {items_.data() + start_[k], items_.data() + start_[k + 1]};
}

}  // namespace tinlod
