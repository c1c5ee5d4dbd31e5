// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

namespace tinlod {

// Ctrl-C (SIGINT), SIGTERM and SIGHUP for a process run from a terminal or a script: the
// command line, and qgis_process while a tinlod algorithm runs (Python's own handler would
// only note the signal, so the run went on to the end).
//
// The first signal makes stopRequested() true, and the work stops at its next progress
// report, leaving no output. Some steps cannot be interrupted (a driver closing a file, a
// spatial index being built): when the work has not stopped a second later, or at a second
// signal, the staging folders are removed and the process exits at once with status 130.
// A commit in progress is finished first, so outputs are all in place or none.
void catchStopSignals();
// Puts back the handlers that were there before (a host process such as qgis_process).
void releaseStopSignals();
bool stopRequested();

}  // namespace tinlod
