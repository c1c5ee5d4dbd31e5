// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <functional>
#include <memory>
#include <string>

namespace tinlod {

// How long-running core work talks to its caller. Every front end (command line,
// QGIS Processing, tests) adapts to this one struct.
struct Feedback {
  // Fraction done in [0, 1] and the current phase; return false to cancel.
  std::function<bool(double fraction, const std::string& phase)> progress;
  // Something the user should know that does not stop the work.
  std::function<void(const std::string& message)> warning;
  // Plain information (chosen CRS, counts).
  std::function<void(const std::string& message)> info;
};

// A view of a Feedback that maps [0, 1] onto [start, end] of the parent's range, so
// that a step can report its own progress without knowing where it sits in the job.
// Holds its own (shared) copy of the Feedback, so a temporary is safe to pass.
class ProgressRange {
 public:
  ProgressRange(Feedback feedback, double start, double end);

  // Reports progress; throws Cancelled when the callback asks to stop.
  void report(double fraction, const std::string& phase) const;
  // Reports the end of the range once the work is committed: a cancel asked for now
  // comes too late to honour, so it is not turned into Cancelled.
  void finish(const std::string& phase) const;
  void warn(const std::string& message) const;
  void inform(const std::string& message) const;
  ProgressRange sub(double start, double end) const;

 private:
  ProgressRange(std::shared_ptr<const Feedback> feedback, double start, double end);
  std::shared_ptr<const Feedback> feedback_;
  double start_;
  double end_;
};

}  // namespace tinlod
