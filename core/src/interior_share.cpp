// SPDX-License-Identifier: GPL-3.0-or-later
#include "interior_share.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "text_and_paths.h"
#include "tinlod/hierarchy_options.h"

namespace tinlod {
namespace {

std::size_t interior(const LevelStats& l) { return l.vertices - std::min(l.vertices, l.outlineVertices); }

std::string percent(double part, double whole, int decimals) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(decimals) << 100.0 * part / whole;
  return out.str();
}

// The -stop_pct, in the fewest decimals, that stops the builder right after level n. Its
// count, ceil(p % of level 0's vertices), is at least level n's, so the builder stops there;
// rounded up, it may cut level n's deletions a little, but leaves them 1 % of level n-1's
// vertices or more, so that level n is still made (the builder's rule for a level).
std::string stopPctFor(const std::vector<LevelStats>& levels, std::size_t n) {
  const double all = double(levels.front().vertices);
  const std::size_t before = levels[n - 1].vertices;
  for (int decimals = 1; decimals <= 6; ++decimals) {
    const double scale = std::pow(10.0, decimals);
    const double p = std::ceil(100.0 * double(levels[n].vertices) / all * scale) / scale;
    const auto count = static_cast<std::size_t>(std::ceil(p / 100.0 * all));
    if (count < before && before - count >= before / kMinLevelShare) {
      std::ostringstream out;
      out << std::fixed << std::setprecision(decimals) << p;
      return out.str();
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
