// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the three formats of writeAccuracyReport, each writing the whole report to
// a stream that writeAccuracyReport then commits atomically.
#pragma once

#include <ostream>

#include "tinlod/accuracy_report.h"

namespace tinlod {

void writeCsvReport(const AccuracyReport& report, std::ostream& out);
void writeJsonReport(const AccuracyReport& report, std::ostream& out);
void writeHtmlReport(const AccuracyReport& report, std::ostream& out);

}  // namespace tinlod
