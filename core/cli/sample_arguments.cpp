// SPDX-License-Identifier: GPL-3.0-or-later
#include "sample_arguments.h"

namespace tinlod::cli {

SampleOptions sampleOptions(Arguments& a) {
  SampleOptions options;
  options.band = a.integer("-b", options.band);
  options.sourceSrs = a.text("-s_srs", options.sourceSrs);
  options.targetSrs = a.text("-t_srs", options.targetSrs);
  options.block = a.integer("-block", options.block);
  options.jitter = a.number("-jitter", options.jitter);
  options.seed = a.unsignedInteger("-seed", options.seed);
  return options;
}

}  // namespace tinlod::cli
