// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include "tinlod/feedback.h"

namespace tinlod::cli {

// GDAL-style progress ("0...10...20...done") and messages on stderr; quiet keeps
// only warnings.
Feedback terminalFeedback(bool quiet);

}  // namespace tinlod::cli
