// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <optional>

#include "arguments.h"
#include "tinlod/sample_options.h"

namespace tinlod::cli {

// -valid_range min max, the heights a DEM cell may hold; none when not given.
std::optional<HeightRange> validRange(Arguments& a);

// The sampling options shared by `tinlod sample` and `tinlod build`.
SampleOptions sampleOptions(Arguments& a);

}  // namespace tinlod::cli
