// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/feedback.h"

#include <algorithm>

#include "tinlod/error.h"

namespace tinlod {

ProgressRange::ProgressRange(Feedback feedback, double start, double end)
    : ProgressRange(std::make_shared<const Feedback>(std::move(feedback)), start, end) {}

ProgressRange::ProgressRange(std::shared_ptr<const Feedback> feedback, double start, double end)
    : feedback_(std::move(feedback)), start_(start), end_(end) {}

void ProgressRange::report(double fraction, const std::string& phase) const {
  if (!feedback_->progress) return;
  const double f = std::clamp(fraction, 0.0, 1.0);
  if (!feedback_->progress(start_ + f * (end_ - start_), phase)) throw Cancelled();
}

void ProgressRange::finish(const std::string& phase) const {
  if (feedback_->progress) feedback_->progress(end_, phase);
}

void ProgressRange::warn(const std::string& message) const {
  if (feedback_->warning) feedback_->warning(message);
}

void ProgressRange::inform(const std::string& message) const {
  if (feedback_->info) feedback_->info(message);
}

ProgressRange ProgressRange::sub(double start, double end) const {
  const double span = end_ - start_;
  return ProgressRange(feedback_, start_ + start * span, start_ + end * span);
}

}  // namespace tinlod
