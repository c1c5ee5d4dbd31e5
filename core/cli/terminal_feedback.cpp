// SPDX-License-Identifier: GPL-3.0-or-later
#include "terminal_feedback.h"

#include <cpl_progress.h>

#include <iostream>

namespace tinlod::cli {

Feedback terminalFeedback(bool quiet) {
  Feedback feedback;
  feedback.warning = [](const std::string& m) { std::cerr << "Warning: " << m << std::endl; };
  if (quiet) return feedback;
  feedback.info = [](const std::string& m) { std::cerr << m << std::endl; };
  feedback.progress = [](double fraction, const std::string&) {
    return GDALTermProgress(fraction, nullptr, nullptr) != 0;
  };
  return feedback;
}

}  // namespace tinlod::cli
