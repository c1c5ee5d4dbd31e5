// SPDX-License-Identifier: GPL-3.0-or-later
// Private: each vertex's ring of neighbours as TIN ids, half a cache line a vertex, written
// whenever the simplifier measures a vertex again (its star changed). The best-first pick
// blocks a picked vertex's neighbours in importance order, which jumps about the TIN:
// there one line is read where a star walk would wait on each of its triangles in turn.
// Rings of up to 7 (most of a Delaunay TIN's, whose mean degree is 6) are kept: 15 took
// twice the memory (120 MB on a 4096 x 4096 tile) for no measurable speed on alps_2x2.
#pragma once

#include <cstdint>
#include <memory>

#include "tinlod/tin.h"

namespace tinlod {

class VertexRings {
 public:
  static constexpr int kCapacity = 7;  // larger rings are walked in the mesh instead

  // The rows are left unwritten: each is written when its vertex is first measured, on
  // the core that measures it, before anything reads it.
  void reset(std::size_t vertices) { rows_.reset(new Row[vertices]); }
  // Where the ring of v is written; then its degree (the ring is kept only up to kCapacity).
  VertexId* place(VertexId v) { return rows_[v].ids; }
  void setDegree(VertexId v, int degree) { rows_[v].degree = degree; }

  int degree(VertexId v) const { return rows_[v].degree; }
  bool kept(VertexId v) const { return rows_[v].degree <= kCapacity; }
  const VertexId* ring(VertexId v) const { return rows_[v].ids; }
  void prefetch(VertexId v) const { __builtin_prefetch(&rows_[v]); }

 private:
  struct alignas(32) Row {
    std::int32_t degree;
    VertexId ids[kCapacity];
  };
  std::unique_ptr<Row[]> rows_;
};

}  // namespace tinlod
