// SPDX-License-Identifier: GPL-3.0-or-later
// Private: how greedy insertion finds a triangle's worst candidate.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "tinlod/greedy_inserter.h"
#include "tinlod/triangle_plane.h"

namespace tinlod {

struct ScanResult {
  // The largest vertical error of a candidate inside the triangle (closed) other than its
  // corners; infinity when the triangle must be split off a hole.
  double error = 0;
  std::uint32_t candidate = 0;
  bool overHole = false;  // a missing cell's centre lies in the closed triangle
};

// Scans triangles of candidate ids over the grid: by exact integer spans when every cell
// is a candidate (the common case, and the fast one), by cell blocks when the candidates
// are sampled points.
class CandidateScanner {
 public:
  explicit CandidateScanner(const InsertGrid& grid);

  ScanResult scan(const std::array<std::uint32_t, 3>& corners) const;
  double col(std::uint32_t id) const;
  double row(std::uint32_t id) const;
  // Candidates that include every extreme point of the candidate set (for its hull).
  std::vector<std::uint32_t> hullCandidates() const;

 private:
  struct CellBlock {
    int r0, r1, c0, c1;  // rows and columns, inclusive
  };

  double height(std::uint32_t id) const;
  TrianglePlane planeOf(const std::array<std::uint32_t, 3>& corners) const;  // in cell units
  CellBlock blockAround(const std::array<std::uint32_t, 3>& corners) const;
  template <bool kHoles>
  ScanResult scanCells(std::array<std::uint32_t, 3> corners) const;
  ScanResult scanSamples(const std::array<std::uint32_t, 3>& corners) const;
  std::uint32_t splitCandidate(const std::array<std::uint32_t, 3>& corners) const;
  bool inside(const std::array<std::uint32_t, 3>& corners, double col, double row) const;
  bool footprintHolds(const std::array<std::uint32_t, 3>& corners, int col, int row) const;
  bool valid(std::size_t cell) const { return grid_.z[cell] == grid_.z[cell]; }

  const InsertGrid& grid_;
  bool holes_ = false;
  std::vector<std::uint8_t> edgeOfHole_;    // valid cells with a missing 8-neighbour
  std::vector<std::int32_t> sampleOfCell_;  // samples mode: the candidate in each cell, or -1
};

}  // namespace tinlod
