// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <optional>

#include "arguments.h"
#include "tinlod/sample_options.h"

namespace tinlod::cli {

// -valid_range min max, the heights a DEM cell may hold; none when not given. `fallback`:
// the range a command takes when none is given, which given is no option in effect.
std::optional<HeightRange> validRange(Arguments& a, const std::optional<HeightRange>& fallback = std::nullopt);

// The sampling options shared by `tinlod sample` and `tinlod build`.
SampleOptions sampleOptions(Arguments& a);

}  // namespace tinlod::cli
