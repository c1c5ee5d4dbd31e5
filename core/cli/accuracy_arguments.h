// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <ostream>
#include <vector>

#include "arguments.h"
#include "tinlod/accuracy_raster.h"
#include "tinlod/accuracy_job.h"

namespace tinlod::cli {

// The accuracy options shared by `tinlod accuracy` and `tinlod build`.
AccuracyOutputs accuracyOutputs(Arguments& a);

extern const char* const kAccuracyHelp;

// A few columns per level: what a person checks first.
void printAccuracy(const std::vector<LevelAccuracy>& rows, std::ostream& out);

}  // namespace tinlod::cli
