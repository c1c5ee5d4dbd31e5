// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "tinlod/dem.h"
#include "tinlod/feedback.h"

namespace tinlod {

// Takes a DEM's cell centres into the metric CRS the TIN is built in. Heights are
// never resampled: only x and y of the sample points move.
class CrsTransform {
 public:
  // The target is `targetSrs` when given (any GDAL/PROJ definition: "EPSG:32632",
  // WKT, PROJ string); otherwise the DEM's own CRS when its units are metres, and
  // else the UTM zone of the DEM's centre. A DEM without a CRS stays in its own
  // units, which are assumed to be metres (a warning says so). `sourceSrs`, when
  // given, replaces the DEM's own CRS.
  static CrsTransform forDem(const Dem& dem, const std::string& sourceSrs, const std::string& targetSrs,
                             const ProgressRange& progress);

  CrsTransform(CrsTransform&&) noexcept;
  CrsTransform& operator=(CrsTransform&&) noexcept;
  ~CrsTransform();

  bool isIdentity() const;
  const std::string& targetWkt() const;   // empty when the DEM had no CRS
  // The DEM's CRS as read: -s_srs when given, else the file's own; empty when it has none.
  const std::string& sourceWkt() const;
  const std::string& targetName() const;  // "WGS 84 / UTM zone 32N", for messages

  // Transforms in place; throws Error if PROJ cannot transform a point.
  void apply(std::vector<double>& x, std::vector<double>& y) const;
  // From the TIN's CRS back to the DEM's, in place: where the accuracy of a TIN is
  // measured on the DEM's own grid.
  void applyInverse(std::vector<double>& x, std::vector<double>& y) const;
  // Metres between two points of the DEM's CRS, measured in the TIN's.
  double groundDistance(double x0, double y0, double x1, double y1) const;

 private:
  struct Impl;
  explicit CrsTransform(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// The UTM zone (EPSG:326zz north, EPSG:327zz south) containing a WGS 84 point.
int utmEpsgFor(double lonDegrees, double latDegrees);

}  // namespace tinlod
