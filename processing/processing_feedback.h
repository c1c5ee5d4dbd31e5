// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <qgsexception.h>
#include <qgsprocessingfeedback.h>

#include <exception>

#include "tinlod/feedback.h"

namespace tinlod::qgis {

// The core's Feedback over a QgsProcessingFeedback: progress bar, phase text, warnings,
// information, and cancellation from the dialog's Cancel button.
Feedback processingFeedback(QgsProcessingFeedback* feedback);

// Runs core work, turning tinlod::Error (and any std::exception) into the
// QgsProcessingException that QGIS shows the user.
template <typename Work>
auto translateErrors(Work&& work) -> decltype(work()) {
  try {
    return work();
  } catch (const std::exception& e) {
    throw QgsProcessingException(QString::fromStdString(e.what()));
  }
}

}  // namespace tinlod::qgis
