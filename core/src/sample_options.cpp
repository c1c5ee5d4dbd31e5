// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/sample_options.h"

#include <cmath>

#include "text_and_paths.h"
#include "tinlod/error.h"

namespace tinlod {

void SampleOptions::validate() const {
  if (band < 1) throw Error("-b must be 1 or more (got " + std::to_string(band) + ")");
  if (block < 1 || block > 1000)
    throw Error("-block must be a whole number from 1 to 1000 (got " + std::to_string(block) +
                "); 3 is the study's choice, 1 takes every cell");
  if (!std::isfinite(jitter) || jitter < 0 || jitter > 1000)
    throw Error("-jitter must be from 0 to 1000 metres (got " + formatNumber(jitter) +
                "); the default 0.99 keeps points off common circles");
  validHeights.validate();
}

void SampleOptions::validateForHierarchy() const {
  validate();
  if (!(jitter > 0))
    throw Error("-jitter must be more than 0 metres to build a hierarchy (got 0): without it vertices sit on cell "
                "centres and edges run through them, and no cell could be measured exactly once; use e.g. -jitter 0.01");
}

}  // namespace tinlod
