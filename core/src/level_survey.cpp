// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/level_survey.h"

#include <sstream>

#include "tinlod/tile_borders.h"

namespace tinlod {
namespace {

// The bins with a count, as [bin, count] pairs.
void bins(std::ostream& out, const std::vector<std::uint64_t>& counts) {
  bool first = true;
  for (std::size_t b = 0; b < counts.size(); ++b)
    if (counts[b]) out << (first ? "" : ", ") << "[" << b << ", " << counts[b] << "]", first = false;
}

}  // namespace

std::string surveyJson(const std::vector<LevelSurvey>& levels, const std::vector<std::uint64_t>& lineOutline) {
  std::ostringstream out;
  out.precision(17);
  out << "{\"bins_per_decade\": 200, \"lowest\": 1e-12, \"levels\": [";
  for (std::size_t i = 0; i < levels.size(); ++i) {
    const LevelSurvey& l = levels[i];
    out << (i ? ",\n" : "\n") << "{\"level\": " << l.level << ", \"vertices\": " << l.vertices << ", \"picked\": " << l.picked
        << ", \"considered\": " << l.considered << ", \"last\": " << l.last << ", \"histogram\": [";
    bins(out, l.histogram);
    out << "], \"picked_histogram\": [";
    bins(out, l.pickedHistogram);
    out << "]";
    if (!l.walkHistogram.empty()) {
      out << ", \"walk_histogram\": [";
      bins(out, l.walkHistogram);
      out << "]";
    }
    out << ", \"union_vertices\": " << l.unionVertices << ", \"border_picked\": " << l.borderPicked << "}";
  }
  out << "\n], \"line_outline\": [";
  for (std::size_t i = 0; i < lineOutline.size(); ++i)
    out << (i ? ", " : "") << "[" << globalCellRow(lineOutline[i]) << ", " << globalCellCol(lineOutline[i]) << "]";
  out << "]}\n";
  return out.str();
}

}  // namespace tinlod
