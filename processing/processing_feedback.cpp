// SPDX-License-Identifier: GPL-3.0-or-later
#include "processing_feedback.h"

#include <memory>

namespace tinlod::qgis {

Feedback processingFeedback(QgsProcessingFeedback* feedback) {
  Feedback out;
  if (!feedback) return out;
  auto lastPhase = std::make_shared<std::string>();
  out.progress = [feedback, lastPhase](double fraction, const std::string& phase) {
    if (phase != *lastPhase) {
      feedback->setProgressText(QString::fromStdString(phase));
      *lastPhase = phase;
    }
    feedback->setProgress(100.0 * fraction);
    return !feedback->isCanceled();
  };
  out.warning = [feedback](const std::string& m) { feedback->pushWarning(QString::fromStdString(m)); };
  out.info = [feedback](const std::string& m) { feedback->pushInfo(QString::fromStdString(m)); };
  return out;
}

}  // namespace tinlod::qgis
