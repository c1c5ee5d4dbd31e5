// SPDX-License-Identifier: GPL-3.0-or-later
#include "sample_arguments.h"

namespace tinlod::cli {

std::optional<HeightRange> validRange(Arguments& a, const std::optional<HeightRange>& fallback) {
  const std::vector<double> range =
      a.numbers("-valid_range", 2, fallback ? std::vector<double>{fallback->min, fallback->max} : std::vector<double>{});
  if (range.empty()) return std::nullopt;
  return HeightRange{range[0], range[1]};
}

SampleOptions sampleOptions(Arguments& a) {
  SampleOptions options;
  options.band = a.integer("-b", options.band);
  options.sourceSrs = a.text("-s_srs", options.sourceSrs);
  options.targetSrs = a.text("-t_srs", options.targetSrs);
  options.block = a.integer("-block", options.block);
  options.jitter = a.number("-jitter", options.jitter);
  options.seed = a.unsignedInteger("-seed", options.seed);
  options.validHeights = validRange(a, options.validHeights).value_or(options.validHeights);
  return options;
}

}  // namespace tinlod::cli
