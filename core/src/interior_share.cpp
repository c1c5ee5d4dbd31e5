// SPDX-License-Identifier: GPL-3.0-or-later
#include "interior_share.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <sstream>

#include "text_and_paths.h"

namespace tinlod {
namespace {

std::size_t interior(const LevelStats& l) { return l.vertices - std::min(l.vertices, l.outlineVertices); }

std::string percent(double part, double whole, int decimals) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(decimals) << 100.0 * part / whole;
  return out.str();
}

// The -stop_pct, in the fewest decimals, whose count (the builder's ceil(p % of level 0's
// vertices), from p as typed) is level n's exactly: the builder then stops right after level
// n, which deletes what it deleted here, so its figures are the ones this warning gives.
std::string stopPctFor(const std::vector<LevelStats>& levels, std::size_t n) {
  const double all = double(levels.front().vertices), exact = 100.0 * double(levels[n].vertices) / all;
  for (int decimals = 1; decimals <= 9; ++decimals) {
    const double scale = std::pow(10.0, decimals);
    for (const double candidate : {std::floor(exact * scale) / scale, std::ceil(exact * scale) / scale}) {
      std::ostringstream out;
      out << std::fixed << std::setprecision(decimals) << candidate;
      const double typed = std::strtod(out.str().c_str(), nullptr);
      if (static_cast<std::size_t>(std::ceil(typed / 100.0 * all)) == levels[n].vertices) return out.str();
    }
  }
  return {};
}

}  // namespace

std::string starvedInteriorWarning(const std::vector<LevelStats>& levels, double stopPct) {
  if (levels.size() < 2) return {};
  const double share = stopPct / 100.0, first = double(interior(levels.front()));
  const double last = double(interior(levels.back()));
  if (first == 0 || last >= share / 2 * first) return {};
  std::string text = "the coarsest level keeps " + std::to_string(interior(levels.back())) + " of level 0's " +
                     std::to_string(interior(levels.front())) + " vertices off the outline (" + percent(last, first, 2) +
                     " %), far under the " + formatNumber(stopPct) + " % asked for: the outline's vertices stay, so the "
                     "levels went on deleting the inside alone";
  std::size_t n = 0;  // the last level that keeps the share
  while (n + 1 < levels.size() && double(interior(levels[n + 1])) >= share * first) ++n;
  const std::string pct = n == 0 ? std::string() : stopPctFor(levels, n);
  if (pct.empty()) return text;
  text += "; -stop_pct " + pct + " stops at level " + std::to_string(n) + ", which keeps " +
          percent(double(interior(levels[n])), first, 1) + " % of them";
  const double rmse = levels[n].rmse, coarsest = levels.back().rmse;
  if (rmse > 0 && coarsest > 0 && std::isfinite(rmse) && std::isfinite(coarsest))
    text += " (RMSE " + formatNumber(rmse) + " m against " + formatNumber(coarsest) + " m)";
  return text;
}

}  // namespace tinlod
