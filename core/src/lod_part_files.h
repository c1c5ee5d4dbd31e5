// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the tiles' parts of a catalogue's level-of-detail TIN, kept on disk between
// extracting them and writing the output, so that the output is never held whole.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "extracted_lod.h"

namespace tinlod {

// One tile's part: its extracted TIN (rows and columns the raster's) and, of its vertices,
// those on a line another tile shares.
struct TileLodPart {
  ExtractedLod lod;
  std::vector<std::uint8_t> onLine;
};

// A file a tile in `folder`, which is made here and removed with everything in it when
// this goes (a failed job's staging folder would be removed anyway; a finished job's must
// hold only its outputs).
class LodPartFiles {
 public:
  explicit LodPartFiles(std::filesystem::path folder);
  ~LodPartFiles();
  LodPartFiles(const LodPartFiles&) = delete;
  LodPartFiles& operator=(const LodPartFiles&) = delete;

  // Replaces what tile `tile` held.
  void write(std::size_t tile, const TileLodPart& part) const;
  TileLodPart read(std::size_t tile) const;

 private:
  std::filesystem::path fileOf(std::size_t tile) const;
  std::filesystem::path folder_;
};

}  // namespace tinlod
