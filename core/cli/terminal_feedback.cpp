// SPDX-License-Identifier: GPL-3.0-or-later
#include "terminal_feedback.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>

namespace tinlod::cli {
namespace {

// GDALTermProgress's format ("0...10...20...", one mark per 2.5 %), but on stderr:
// stdout carries the command's results.
class TermProgress {
 public:
  bool operator()(double fraction) {
    const int step = static_cast<int>(std::floor(std::clamp(fraction, 0.0, 1.0) * 40 + 1e-9));
    while (printed_ < step) {  // step 0 prints the opening "0"
      ++printed_;
      if (printed_ % 4 == 0) std::cerr << printed_ / 4 * 10;
      else std::cerr << '.';
    }
    if (step == 40 && !done_) {
      std::cerr << " - done." << std::endl;
      done_ = true;
    }
    std::cerr.flush();
    return true;
  }

 private:
  int printed_ = -1;
  bool done_ = false;
};

}  // namespace

Feedback terminalFeedback(bool quiet) {
  Feedback feedback;
  feedback.warning = [](const std::string& m) { std::cerr << "Warning: " << m << std::endl; };
  if (quiet) return feedback;
  feedback.info = [](const std::string& m) { std::cerr << m << std::endl; };
  auto progress = std::make_shared<TermProgress>();
  feedback.progress = [progress](double fraction, const std::string&) { return (*progress)(fraction); };
  return feedback;
}

}  // namespace tinlod::cli
