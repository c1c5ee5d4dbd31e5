// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include "arguments.h"
#include "tinlod/sample_options.h"

namespace tinlod::cli {

// The sampling options shared by `tinlod sample` and `tinlod build`.
SampleOptions sampleOptions(Arguments& a);

}  // namespace tinlod::cli
