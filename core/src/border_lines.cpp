// SPDX-License-Identifier: GPL-3.0-or-later
#include "border_lines.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>


namespace tinlod {
BorderLines::BorderLines(const Tin& base, const Dem& dem, const TileBorders& tile) : cellArea_(tile.cellArea) {
  std::unordered_map<std::uint64_t, VertexId> vertexOf;  // the vertices on the shared lines, by cell of the tile
  for (VertexId v = 0; v < base.vertices.size(); ++v)
    if (tile.side[v] >= 0) vertexOf.emplace(globalCellKey(base.vertices[v].row, base.vertices[v].col), v);
  for (int s = 0; s < 4; ++s) {
    if (tile.lineClass[s] < 0) continue;
    Line line;
    line.lineClass = tile.lineClass[s];
    const bool column = s == kFirstCol || s == kLastCol;
    for (const auto& [row, col] : lineVertexCells(dem, s, tile.block, tile.seed)) {
      const auto found = vertexOf.find(globalCellKey(row, col));
      const VertexId v = found == vertexOf.end() ? kNoVertex : found->second;
      // The cell's place, not its vertex's: the other tile may have left the vertex out.
      const double along = column ? double(dem.globalRow(row)) : double(dem.globalCol(col));
      line.cells.push_back({v, dem.at(row, col), along, pinnedBorderCell(dem, tile, row, col)});
    }
    lines_.push_back(std::move(line));
  }
}

std::vector<std::pair<double, VertexId>> BorderLines::take(int level, double share, Limit limit) {
  std::vector<VertexId> refused;
  return take(level, share, limit, [](VertexId) { return true; }, refused);
}

std::vector<std::pair<double, VertexId>> BorderLines::take(int level, double share, Limit limit,
                                                           const std::function<bool(VertexId)>& accept,
                                                           std::vector<VertexId>& refused) {
  std::vector<std::pair<double, VertexId>> out;
  for (Line& line : lines_) {
    if ((level - 1) % 4 != line.lineClass) continue;
    for (;;) {
      const std::vector<Choice> chosen = choose(line, share, limit);
      bool again = false;
      for (const Choice& c : chosen) {
        const VertexId v = line.cells[c.at].vertex;
        if (v != kNoVertex && !accept(v)) {  // only this tile has the vertex to check
          line.cells[c.at].pinned = true;
          refused.push_back(v);
          again = true;
        }
      }
      if (again) continue;
      for (const Choice& c : chosen) out.emplace_back(c.importance, line.cells[c.at].vertex);
      drop(line, chosen);
      break;
    }
  }
  return out;
}

std::vector<BorderLines::Choice> BorderLines::choose(const Line& line, double share, Limit limit) const {
  const std::vector<Cell>& cells = line.cells;
  const std::size_t n = cells.size();
  std::vector<Choice> candidates, chosen;
  if (n < 3) return chosen;
  for (std::size_t i = 1; i + 1 < n; ++i) {
    if (cells[i].pinned) continue;
    const Cell &a = cells[i - 1], &b = cells[i + 1];
    const double f = (cells[i].along - a.along) / (b.along - a.along);
    const double deviation = std::fabs(cells[i].z - (a.z + f * (b.z - a.z)));
    // The volume measure's estimate from the line alone: a cone of that height over a star
    // reaching the line neighbours, as far across the line as along it (a rhombus whose
    // diagonals are both `span`). The other tile, which shares the line, finds the same.
    const double span = b.along - a.along;
    const double volume = deviation * span * span * cellArea_ / 6;
    if (limit.kind == Limit::kVolume) {
      if (volume < limit.below) candidates.push_back({volume, i});
    } else if (limit.kind == Limit::kNone || deviation <= limit.below) {
      candidates.push_back({deviation, i});
    }
  }
  // Ties go to the cell first along the line: nothing but the line decides.
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Choice& a, const Choice& b) { return a.importance < b.importance; });
  const std::size_t most = static_cast<std::size_t>(std::floor(share * double(n - 2)));
  std::vector<std::uint8_t> blocked(n, 0);
  for (const Choice& c : candidates) {
    if (chosen.size() >= most) break;
    if (blocked[c.at]) continue;
    blocked[c.at] = blocked[c.at - 1] = blocked[c.at + 1] = 1;
    chosen.push_back(c);
  }
  return chosen;
}

void BorderLines::drop(Line& line, const std::vector<Choice>& chosen) {
  std::vector<std::uint8_t> gone(line.cells.size(), 0);
  for (const Choice& c : chosen) gone[c.at] = 1;
  std::size_t k = 0;
  for (std::size_t i = 0; i < line.cells.size(); ++i)
    if (!gone[i]) line.cells[k++] = line.cells[i];
  line.cells.resize(k);
}

}  // namespace tinlod
