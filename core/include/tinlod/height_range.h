// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace tinlod {

// The heights a DEM cell may hold and still be ground. Fill values a file does not declare
// as nodata (1e30, -32768, infinity) would otherwise become vertices miles up or down and
// wreck every error figure; the default spans the Earth's surface with room to spare.
struct HeightRange {
  double min = -12000;  // metres: below the deepest ocean trench (-10 994 m)
  double max = 9000;    // metres: above Everest (8 849 m)

  bool contains(float z) const { return z >= min && z <= max; }  // false for NaN and infinity
  // Throws Error naming -valid_range unless min < max, both finite.
  void validate() const;
  // "-12000..9000 m", as messages and metadata give it.
  std::string text() const;
};

// The range written by text(), as a GeoPackage's metadata records it; throws Error otherwise.
HeightRange parseHeightRange(const std::string& text);

// The range a tinlod GeoPackage records in its metadata (key "valid_range"); the default
// for files written before it was recorded.
HeightRange recordedRange(const std::map<std::string, std::string>& metadata);

// Sets to NaN (missing) every height that is neither NaN nor in `range`; returns how many.
std::size_t dropHeightsOutside(std::vector<float>& z, const HeightRange& range);

}  // namespace tinlod
