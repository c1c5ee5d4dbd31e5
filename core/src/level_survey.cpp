// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/level_survey.h"

#include <sstream>

#include "tinlod/tile_borders.h"

namespace tinlod {

std::string surveyJson(const std::vector<LevelSurvey>& levels, const std::vector<std::uint64_t>& lineOutline) {
  std::ostringstream out;
  out.precision(17);
  out << "{\"bins_per_decade\": 200, \"lowest\": 1e-12, \"levels\": [";
  for (std::size_t i = 0; i < levels.size(); ++i) {
    const LevelSurvey& l = levels[i];
    out << (i ? ",\n" : "\n") << "{\"level\": " << l.level << ", \"vertices\": " << l.vertices << ", \"picked\": " << l.picked
        << ", \"considered\": " << l.considered << ", \"last\": " << l.last << ", \"histogram\": [";
    bool first = true;
    for (std::size_t b = 0; b < l.histogram.size(); ++b)
      if (l.histogram[b]) out << (first ? "" : ", ") << "[" << b << ", " << l.histogram[b] << "]", first = false;
    out << "]}";
  }
  out << "\n], \"line_outline\": [";
  for (std::size_t i = 0; i < lineOutline.size(); ++i)
    out << (i ? ", " : "") << "[" << globalCellRow(lineOutline[i]) << ", " << globalCellCol(lineOutline[i]) << "]";
  out << "]}\n";
  return out.str();
}

}  // namespace tinlod
