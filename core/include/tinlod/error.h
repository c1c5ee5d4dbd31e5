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

// Thrown when a DEM's valid cells make no triangle (isolated, or in a line).
class NoTriangle : public Error {
 public:
  explicit NoTriangle(const std::string& message) : Error(message) {}
};

// Thrown for a tile of a raster that holds too little data for a TIN: nothing is
// written, and a tiled run records the tile as empty rather than failed.
class EmptyTile : public Error {
 public:
  explicit EmptyTile(const std::string& message) : Error(message) {}
};

}  // namespace tinlod
