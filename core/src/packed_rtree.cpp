// SPDX-License-Identifier: GPL-3.0-or-later
#include "packed_rtree.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>

#include "release_memory.h"

namespace tinlod {
namespace {

// SQLite's own constants (ext/rtree/rtree.c): a nudge of one float ulp's worth.
constexpr double kTowards = 1.0 - 1.0 / 8388608.0;
constexpr double kAway = 1.0 + 1.0 / 8388608.0;
constexpr int kMaxCells = 51;  // RTREE_MAXCELLS
constexpr int kCellBytes = 8 + 4 * 4;

float down(double d) {
  float f = static_cast<float>(d);
  if (f > d) f = static_cast<float>(d * (d < 0 ? kAway : kTowards));
  return f;
}

float up(double d) {
  float f = static_cast<float>(d);
  if (f < d) f = static_cast<float>(d * (d < 0 ? kTowards : kAway));
  return f;
}

void putBigEndian(unsigned char* at, std::uint64_t value, int bytes) {
  for (int k = bytes - 1; k >= 0; --k, value >>= 8) at[k] = static_cast<unsigned char>(value & 0xFF);
}

void putFloat(unsigned char* at, float value) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, 4);
  putBigEndian(at, bits, 4);
}

// Looks at `abandon` every 16,384 comparisons of a packing's sorts, where it spends its time
// and where nothing else could stop it. One count for all of them: std::sort copies its
// comparison at every step of its recursion, and the y sorts are of one slice (14,000 boxes
// for a million) each.
class AbandonWatch {
 public:
  explicit AbandonWatch(const std::atomic<bool>* abandon) : abandon_(abandon) {}
  void tick() {
    if (abandon_ && (++calls_ & 0x3FFF) == 0 && abandon_->load(std::memory_order_relaxed)) throw PackingAbandoned{};
  }
  template <class Less>
  auto watching(Less less) {
    return [less, this](std::uint64_t a, std::uint64_t b) {
      tick();
      return less(a, b);
    };
  }

 private:
  const std::atomic<bool>* abandon_;
  std::uint32_t calls_ = 0;
};

// A float's order as an unsigned integer's (IEEE 754: positives with the sign bit set,
// negatives with every bit flipped); -0 is made +0 first, as the floats compare equal.
std::uint32_t orderBits(float f) {
  f += 0.0f;
  std::uint32_t bits;
  std::memcpy(&bits, &f, 4);
  return (bits & 0x80000000u) ? ~bits : (bits | 0x80000000u);
}

// Sort-tile-recursive: sorted by x into vertical slices of whole nodes, each slice
// sorted by y and cut into nodes. Returns the items in node order.
std::vector<std::uint32_t> strOrder(const std::vector<RtreeBox>& boxes, std::size_t capacity,
                                    const std::atomic<bool>* abandon) {
  const std::size_t n = boxes.size();
  // Each item sorted as one integer, its centre doubled (min + max) above its index: the
  // index breaks ties, so the tree is the same on every machine, and the sorts read one
  // array in order where comparing indices read two boxes each at random (2.3-3x faster).
  // The centres are not kept: the boxes of a big layer are already the packing's largest
  // use of memory.
  const auto keyed = [](float centre, std::uint32_t item) {
    return static_cast<std::uint64_t>(orderBits(centre)) << 32 | item;
  };
  std::vector<std::uint64_t> keys(n);
  for (std::uint32_t i = 0; i < n; ++i) keys[i] = keyed(boxes[i].minX + boxes[i].maxX, i);
  AbandonWatch watch(abandon);
  const auto less = watch.watching(std::less<std::uint64_t>());
  std::sort(keys.begin(), keys.end(), less);
  const std::size_t nodes = (n + capacity - 1) / capacity;
  const auto slices = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(nodes))));
  const std::size_t sliceItems = slices * capacity;
  for (std::size_t begin = 0; begin < n; begin += sliceItems) {
    const std::size_t end = std::min(n, begin + sliceItems);
    for (std::size_t k = begin; k < end; ++k) {
      const auto i = static_cast<std::uint32_t>(keys[k]);
      keys[k] = keyed(boxes[i].minY + boxes[i].maxY, i);
    }
    std::sort(keys.begin() + begin, keys.begin() + end, less);
  }
  std::vector<std::uint32_t> order(n);
  for (std::size_t k = 0; k < n; ++k) order[k] = static_cast<std::uint32_t>(keys[k]);
  return order;
}

}  // namespace

void RtreeBox::extend(const RtreeBox& o) {
  minX = std::min(minX, o.minX), maxX = std::max(maxX, o.maxX);
  minY = std::min(minY, o.minY), maxY = std::max(maxY, o.maxY);
}

RtreeBox outwardBox(const Envelope& e) { return {down(e.minX), up(e.maxX), down(e.minY), up(e.maxY)}; }

int rtreeNodeCapacity(int pageSize) {
  const int nodeBytes = std::min(pageSize - 64, 4 + kCellBytes * kMaxCells);
  return (nodeBytes - 4) / kCellBytes;
}

PackedRtree::PackedRtree(std::vector<RtreeBox> boxes, int nodeCapacity, const std::atomic<bool>* abandon)
    : entryBoxes_(std::move(boxes)), entries_(entryBoxes_.size()), capacity_(nodeCapacity) {
  const auto m = static_cast<std::size_t>(capacity_);
  do {
    const std::vector<RtreeBox>& below = levels_.empty() ? entryBoxes_ : levels_.back().boxes;
    Level level;
    level.children = strOrder(below, m, abandon);
    level.boxes.reserve((below.size() + m - 1) / m);
    for (std::size_t k = 0; k < below.size(); k += m) {
      RtreeBox box = below[level.children[k]];
      for (std::size_t c = k + 1; c < std::min(below.size(), k + m); ++c) box.extend(below[level.children[c]]);
      level.boxes.push_back(box);
    }
    levels_.push_back(std::move(level));
  } while (levels_.back().boxes.size() > 1);
  std::size_t number = 1;
  for (std::size_t l = levels_.size(); l-- > 0;) {
    levels_[l].firstNode = number;
    number += levels_[l].boxes.size();
  }
}

std::size_t PackedRtree::nodes() const { return levels_.front().firstNode + levels_.front().boxes.size() - 1; }

const std::vector<RtreeBox>& PackedRtree::childBoxes(std::size_t level) const {
  return level == 0 ? entryBoxes_ : levels_[level - 1].boxes;
}

void PackedRtree::nodeBlob(std::size_t node, std::size_t nodeBytes, std::vector<unsigned char>& out) const {
  out.assign(nodeBytes, 0);
  std::size_t l = 0;
  while (node < levels_[l].firstNode) ++l;  // levels_ are numbered from the top down
  const Level& level = levels_[l];
  const std::size_t j = node - level.firstNode;
  const std::size_t m = static_cast<std::size_t>(capacity_);
  const std::size_t begin = j * m, end = std::min(level.children.size(), begin + m);
  if (node == 1) putBigEndian(out.data(), static_cast<std::uint64_t>(depth()), 2);
  putBigEndian(out.data() + 2, end - begin, 2);
  const std::vector<RtreeBox>& boxes = childBoxes(l);
  unsigned char* cell = out.data() + 4;
  for (std::size_t k = begin; k < end; ++k, cell += kCellBytes) {
    const std::uint32_t child = level.children[k];
    // A leaf cell holds the feature's id; an inner cell, the child node's number.
    const std::uint64_t id = l == 0 ? child + 1u : levels_[l - 1].firstNode + child;
    putBigEndian(cell, id, 8);
    const RtreeBox& b = boxes[child];
    putFloat(cell + 8, b.minX), putFloat(cell + 12, b.maxX), putFloat(cell + 16, b.minY), putFloat(cell + 20, b.maxY);
  }
}

std::vector<std::uint32_t> PackedRtree::parents() const {
  std::vector<std::uint32_t> parent(nodes() + 1, 0);
  const std::size_t m = static_cast<std::size_t>(capacity_);
  for (std::size_t l = 1; l < levels_.size(); ++l) {
    const Level& level = levels_[l];
    for (std::size_t k = 0; k < level.children.size(); ++k)
      parent[levels_[l - 1].firstNode + level.children[k]] = static_cast<std::uint32_t>(level.firstNode + k / m);
  }
  return parent;
}

void PackedRtree::dropEntryBoxes() { releaseMemory(entryBoxes_); }

std::vector<std::uint32_t> PackedRtree::leaves() const {
  std::vector<std::uint32_t> leaf(entries());
  const Level& level = levels_.front();
  const std::size_t m = static_cast<std::size_t>(capacity_);
  for (std::size_t k = 0; k < level.children.size(); ++k)
    leaf[level.children[k]] = static_cast<std::uint32_t>(level.firstNode + k / m);
  return leaf;
}

}  // namespace tinlod
