// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include "tinlod/feedback.h"

namespace tinlod::cli {

// GDAL-style progress ("0...10...20...") and messages on stderr; quiet keeps only
// warnings. Ctrl-C (SIGINT), SIGTERM and SIGHUP cancel the work cleanly through the
// progress callback: the core then removes what it had begun to write. A second
// signal ends the program at once.
Feedback terminalFeedback(bool quiet);

// Ends a progress line left open, so that a final message starts on its own line.
void breakProgressLine();

}  // namespace tinlod::cli
