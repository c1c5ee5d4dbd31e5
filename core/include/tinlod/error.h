// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <stdexcept>
#include <string>

namespace tinlod {

// The one way the core reports failure: the message names the input and, where
// there is one, the fix. Front ends translate it once (exit code, QgsProcessingException).
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// Thrown when the progress callback asked to stop; nothing has been written.
class Cancelled : public Error {
 public:
  Cancelled() : Error("cancelled by the user") {}
};

}  // namespace tinlod
