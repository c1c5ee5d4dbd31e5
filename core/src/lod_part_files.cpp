// SPDX-License-Identifier: GPL-3.0-or-later
#include "lod_part_files.h"

#include <cerrno>
#include <fstream>
#include <string>
#include <type_traits>

#include "tinlod/error.h"
#include "tinlod/output_files.h"

namespace tinlod {
namespace fs = std::filesystem;
namespace {

// The arrays as they are in memory: the file is read back by the process that wrote it.
template <typename T>
void put(std::ofstream& out, const std::vector<T>& values) {
  static_assert(std::is_trivially_copyable_v<T>);
  const std::uint64_t n = values.size();
  out.write(reinterpret_cast<const char*>(&n), sizeof n);
  out.write(reinterpret_cast<const char*>(values.data()), std::streamsize(n * sizeof(T)));
}

template <typename T>
void get(std::ifstream& in, std::vector<T>& values) {
  std::uint64_t n = 0;
  in.read(reinterpret_cast<char*>(&n), sizeof n);
  values.resize(in ? n : 0);
  in.read(reinterpret_cast<char*>(values.data()), std::streamsize(values.size() * sizeof(T)));
}

// Every array of a part, in the files' order: one list for writing and reading.
template <class Part, class Visit>
void eachArray(Part& part, Visit visit) {
  visit(part.lod.tin.vertices);
  visit(part.lod.tin.triangles);
  visit(part.lod.vertexLevel);
  visit(part.lod.firstLevel);
  visit(part.lod.lastLevel);
  visit(part.onLine);
}

}  // namespace

LodPartFiles::LodPartFiles(fs::path folder) : folder_(std::move(folder)) {
  std::error_code ec;
  fs::create_directories(folder_, ec);
  if (ec) throw Error("cannot make the folder '" + folder_.string() + "' for the tiles' parts of the output: " + ec.message());
}

LodPartFiles::~LodPartFiles() {
  std::error_code ec;
  fs::remove_all(folder_, ec);
}

fs::path LodPartFiles::fileOf(std::size_t tile) const { return folder_ / ("tile_" + std::to_string(tile) + ".part"); }

void LodPartFiles::write(std::size_t tile, const TileLodPart& part) const {
  errno = 0;
  std::ofstream out(fileOf(tile), std::ios::binary | std::ios::trunc);
  eachArray(part, [&out](const auto& values) { put(out, values); });
  out.close();
  if (!out) throw Error("cannot write a tile's part of the output in '" + folder_.string() + "': " + whyWriteFailed(folder_));
}

TileLodPart LodPartFiles::read(std::size_t tile) const {
  std::ifstream in(fileOf(tile), std::ios::binary);
  TileLodPart part;
  eachArray(part, [&in](auto& values) { get(in, values); });
  if (!in) throw Error("cannot read back a tile's part of the output from '" + folder_.string() + "'");
  return part;
}

}  // namespace tinlod
