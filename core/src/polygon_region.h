// SPDX-License-Identifier: GPL-3.0-or-later
// Private: a polygon layer as a region to test points against (GEOS).
#pragma once

#include <array>
#include <memory>
#include <string>

#include "tinlod/feedback.h"

namespace tinlod {

class PolygonRegion {
 public:
  // The union of the polygons of the first layer of a vector file, in the TIN's CRS
  // `targetWkt`. Throws Error naming the file when it has none. `what` names the layer
  // in messages.
  PolygonRegion(const std::string& path, const std::string& targetWkt, const std::string& what, const ProgressRange& progress);
  ~PolygonRegion();
  PolygonRegion(const PolygonRegion&) = delete;
  PolygonRegion& operator=(const PolygonRegion&) = delete;

  // Whether the closed triangle meets the region. Not thread-safe (one GEOS context).
  bool meets(const std::array<std::array<double, 2>, 3>& triangle) const;
  // xmin, ymin, xmax, ymax in the TIN's CRS.
  const std::array<double, 4>& envelope() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tinlod
