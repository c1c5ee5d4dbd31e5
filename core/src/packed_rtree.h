// SPDX-License-Identifier: GPL-3.0-or-later
// Private: an R-tree packed from all its boxes at once (sort-tile-recursive), laid out
// as SQLite's rtree module stores one, so a GeoPackage's spatial index is bulk-loaded
// instead of built row by row.
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "gpkg_geometry_blob.h"

namespace tinlod {

// A box as SQLite's rtree stores it: 32-bit floats, rounded outwards.
struct RtreeBox {
  float minX, maxX, minY, maxY;
  void extend(const RtreeBox& other);
};

// Rounds as SQLite's rtree does when a row is inserted (rtreeValueDown and rtreeValueUp),
// so a packed index holds exactly the boxes a row-by-row one would.
RtreeBox outwardBox(const Envelope& envelope);

// How many cells SQLite's rtree puts in a node of a 2-D index for a database page size.
int rtreeNodeCapacity(int pageSize);

// Thrown by PackedRtree's constructor once `abandon` is set.
struct PackingAbandoned {};

class PackedRtree {
 public:
  // Entry i has id i + 1 (the features' fids) and box boxes[i]. Packing a big layer takes a
  // second or more on a thread beside the writing: once `abandon` (when given) is set, it
  // stops within a few milliseconds, throwing PackingAbandoned, so that a cancelled or failed
  // write does not wait for an index it will never write.
  PackedRtree(std::vector<RtreeBox> boxes, int nodeCapacity, const std::atomic<bool>* abandon = nullptr);

  std::size_t entries() const { return entries_; }
  // Nodes are numbered from 1, the root, level by level down to the leaves.
  std::size_t nodes() const;
  // SQLite's depth of the tree: 0 when the root is a leaf.
  int depth() const { return static_cast<int>(levels_.size()) - 1; }
  // The node's bytes as SQLite stores them, `nodeBytes` long.
  void nodeBlob(std::size_t node, std::size_t nodeBytes, std::vector<unsigned char>& out) const;
  // The parent of every node but the root, indexed by node number (entry 0 and 1 unused).
  std::vector<std::uint32_t> parents() const;
  // The leaf node that holds each entry, indexed by entry (id - 1).
  std::vector<std::uint32_t> leaves() const;
  // Frees the entries' boxes, the tree's largest part, once every node blob is written:
  // leaves() and parents() do not need them, nodeBlob() does.
  void dropEntryBoxes();

 private:
  // Level 0 holds the leaves. Node j of a level has as children the items
  // children[j * capacity_ ...] of the level below (entries for the leaves).
  struct Level {
    std::vector<std::uint32_t> children;
    std::vector<RtreeBox> boxes;
    std::size_t firstNode = 0;  // the number of node 0
  };
  const std::vector<RtreeBox>& childBoxes(std::size_t level) const;
  std::size_t nodeCount(std::size_t level) const { return levels_[level].boxes.size(); }
  std::vector<RtreeBox> entryBoxes_;
  std::size_t entries_ = 0;
  std::vector<Level> levels_;
  int capacity_;
};

}  // namespace tinlod
