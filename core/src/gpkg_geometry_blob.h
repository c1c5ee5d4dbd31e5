// SPDX-License-Identifier: GPL-3.0-or-later
// Private: geometries in the GeoPackage binary format (the spec's header, then ISO WKB),
// encoded straight from coordinates for the bulk writer.
#pragma once

#include <cstdint>
#include <vector>

namespace tinlod {

struct Envelope {
  double minX, maxX, minY, maxY;
  void extend(double x, double y);
  void extend(const Envelope& other);
  static Envelope empty();
  bool isEmpty() const { return minX > maxX; }
};

// One geometry's bytes, rebuilt in place for each feature so rows cost no allocation.
// No envelope is written: the spec makes it optional, GDAL and QGIS compute it from the
// WKB when they need it, and for a triangle GDAL's XYZ envelope took 48 of its 165 bytes.
class GpkgGeometryBlob {
 public:
  explicit GpkgGeometryBlob(std::int32_t srsId) : srsId_(srsId) {}

  void pointZ(double x, double y, double z);
  // A polygon of one ring; the ring is closed here (the first point repeated). With
  // hasZ false, z is ignored and the polygon is 2D.
  template <class PointAt>
  void polygon(std::size_t points, PointAt at, bool hasZ) {
    envelope_ = Envelope::empty();
    begin(hasZ ? 1003 : 3);
    if (points == 0) {  // the empty polygon: no ring
      put32(0);
      return;
    }
    put32(1);
    put32(static_cast<std::uint32_t>(points + 1));
    for (std::size_t k = 0; k <= points; ++k) {
      double x, y, z;
      at(k == points ? 0 : k, x, y, z);
      putPoint(x, y, z, hasZ);
    }
  }

  const unsigned char* data() const { return bytes_.data(); }
  std::size_t size() const { return size_; }
  const Envelope& envelope() const { return envelope_; }

 private:
  void begin(std::uint32_t isoType);
  void put(const void* bytes, std::size_t size);
  void put32(std::uint32_t value);
  void putDouble(double value);
  void putPoint(double x, double y, double z, bool hasZ);
  std::int32_t srsId_;
  std::vector<unsigned char> bytes_;
  std::size_t size_ = 0;
  Envelope envelope_ = Envelope::empty();
};

}  // namespace tinlod
