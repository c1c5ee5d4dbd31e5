// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/height_range.h"

#include <charconv>
#include <cmath>

#include "number_text.h"
#include "text_and_paths.h"
#include "tinlod/error.h"

namespace tinlod {

void HeightRange::validate() const {
  if (!std::isfinite(min) || !std::isfinite(max) || !(min < max))
    throw Error("-valid_range must be two finite heights in metres, the lower first (got " + formatNumber(min) + " " +
                formatNumber(max) + "); the default is -12000 9000");
}

std::string HeightRange::text() const { return roundTripNumber(min) + ".." + roundTripNumber(max) + " m"; }

namespace {

// The whole of [begin, end) as a number; from_chars, not strtod, as QGIS may have set a
// locale with a decimal comma.
bool readNumber(const char* begin, const char* end, double& value) {
  const auto read = std::from_chars(begin, end, value);
  return read.ec == std::errc() && read.ptr == end && std::isfinite(value);
}

}  // namespace

HeightRange parseHeightRange(const std::string& text) {
  HeightRange range;
  const std::size_t dots = text.find("..", 1);  // after a number: "12." would take the first dot
  const bool read = dots != std::string::npos && text.size() > 2 && text.compare(text.size() - 2, 2, " m") == 0 &&
                    readNumber(text.data(), text.data() + dots, range.min) &&
                    readNumber(text.data() + dots + 2, text.data() + text.size() - 2, range.max);
  if (!read || !(range.min < range.max)) throw Error("'" + text + "' is not a height range such as -12000..9000 m");
  return range;
}

HeightRange recordedRange(const std::map<std::string, std::string>& metadata) {
  const auto item = metadata.find("valid_range");
  return item == metadata.end() ? HeightRange{} : parseHeightRange(item->second);
}

std::size_t dropHeightsOutside(std::vector<float>& z, const HeightRange& range) {
  std::size_t dropped = 0;
  for (float& v : z)
    if (!std::isnan(v) && !range.contains(v)) {
      v = NAN;
      ++dropped;
    }
  return dropped;
}

}  // namespace tinlod
