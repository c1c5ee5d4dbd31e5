// SPDX-License-Identifier: GPL-3.0-or-later
#include "terminal_feedback.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>

#include "tinlod/stop_signals.h"

namespace tinlod::cli {
namespace {

bool gMidLine = false;  // a progress line is open on stderr

}  // namespace
void breakProgressLine();
namespace {

// GDALTermProgress's format ("0...10...20...", one mark per 2.5 %), but on stderr:
// stdout carries the command's results. A message in mid-line starts on a new line.
class TermProgress {
 public:
  bool update(double fraction) {
    const int step = static_cast<int>(std::floor(std::clamp(fraction, 0.0, 1.0) * 40 + 1e-9));
    while (printed_ < step) {  // step 0 prints the opening "0"
      ++printed_;
      if (printed_ % 4 == 0) std::cerr << printed_ / 4 * 10;
      else std::cerr << '.';
      gMidLine = true;
    }
    if (step == 40 && !done_) {
      std::cerr << " - done." << std::endl;
      done_ = true;
      gMidLine = false;
    }
    std::cerr.flush();
    return !stopRequested();
  }
  void message(const std::string& prefix, const std::string& text) {
    breakProgressLine();
    std::cerr << prefix << text << std::endl;
  }

 private:
  int printed_ = -1;
  bool done_ = false;
};

}  // namespace

void breakProgressLine() {
  if (gMidLine) std::cerr << '\n';
  gMidLine = false;
}

Feedback terminalFeedback(bool quiet) {
  catchStopSignals();
  auto term = std::make_shared<TermProgress>();
  Feedback feedback;
  feedback.warning = [term](const std::string& m) { term->message("Warning: ", m); };
  if (quiet) {
    feedback.progress = [](double, const std::string&) { return !stopRequested(); };
    return feedback;
  }
  feedback.info = [term](const std::string& m) { term->message("", m); };
  feedback.progress = [term](double fraction, const std::string&) { return term->update(fraction); };
  return feedback;
}

}  // namespace tinlod::cli
