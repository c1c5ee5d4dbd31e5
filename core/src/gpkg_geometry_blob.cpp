// SPDX-License-Identifier: GPL-3.0-or-later
#include "gpkg_geometry_blob.h"

#include <algorithm>
#include <cstring>
#include <limits>

namespace tinlod {

static_assert(sizeof(double) == 8 && std::numeric_limits<double>::is_iec559, "WKB needs IEEE doubles");

Envelope Envelope::empty() {
  const double inf = std::numeric_limits<double>::infinity();
  return {inf, -inf, inf, -inf};
}

void Envelope::extend(double x, double y) {
  minX = std::min(minX, x), maxX = std::max(maxX, x);
  minY = std::min(minY, y), maxY = std::max(maxY, y);
}

void Envelope::extend(const Envelope& other) {
  if (other.isEmpty()) return;
  extend(other.minX, other.minY);
  extend(other.maxX, other.maxY);
}

// Every number is written little-endian, which the header's flags and the WKB byte-order
// byte both declare; the writer only runs on little-endian machines (checked below).
void GpkgGeometryBlob::put(const void* bytes, std::size_t size) {
  // Grown, never shrunk: after the first features a row costs no allocation or zeroing.
  if (size_ + size > bytes_.size()) bytes_.resize(2 * (size_ + size));
  std::memcpy(bytes_.data() + size_, bytes, size);
  size_ += size;
}

void GpkgGeometryBlob::put32(std::uint32_t value) { put(&value, 4); }

void GpkgGeometryBlob::putDouble(double value) { put(&value, 8); }

void GpkgGeometryBlob::putPoint(double x, double y, double z, bool hasZ) {
  putDouble(x);
  putDouble(y);
  if (hasZ) putDouble(z);
  envelope_.extend(x, y);
}

void GpkgGeometryBlob::begin(std::uint32_t isoType) {
  static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the GeoPackage blobs are written little-endian");
  size_ = 0;
  // "GP", version 0, flags: little-endian, no envelope, not empty, standard binary.
  const unsigned char header[4] = {'G', 'P', 0, 0x01};
  put(header, 4);
  put32(static_cast<std::uint32_t>(srsId_));
  const unsigned char littleEndian = 1;  // WKB's byte order
  put(&littleEndian, 1);
  put32(isoType);
}

void GpkgGeometryBlob::pointZ(double x, double y, double z) {
  begin(1001);
  envelope_ = Envelope::empty();
  putPoint(x, y, z, true);
}

}  // namespace tinlod
