// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "tinlod/concavity.h"
#include "tinlod/douglas_peucker.h"
#include "tinlod/feedback.h"

namespace tinlod {

// The lines of the first layer of a vector file, each part of a multi-line its own line,
// in a metric CRS: the layer's own when it is projected, else the UTM zone of its centre
// (as for DEMs). `feature` gives each line's feature id. Vertices that are not finite
// numbers are skipped, and lines they leave with fewer than 2 vertices, with one warning
// that counts them. Throws Error naming the file and the geometry type for a layer of
// points or polygons.
struct LineSet {
  std::vector<Polyline> lines;
  std::vector<long long> feature;
  std::string crsWkt;   // empty when the layer has none (taken as metric, with a warning)
  std::string crsName;
};

LineSet readLines(const std::string& path, const ProgressRange& progress);

// `tinlod lines dp`: every line with its vertices' Douglas-Peucker values as M (LineStringM,
// layer 'lines'; the endpoints' infinity stored as M = 1e300, a value no threshold
// reaches); optionally a point layer 'vertices' (line, vertex, value; null for endpoints);
// and, for a threshold, layer 'simplified' and the count of crossings between simplified
// lines. Written atomically to a GeoPackage.
struct DpOptions {
  bool points = false;
  double threshold = std::numeric_limits<double>::quiet_NaN();  // metres, 0 or more; NaN: no simplified layer
  void validate() const;  // throws Error naming the option
};
struct DpSummary {
  std::size_t lines = 0, vertices = 0, keptVertices = 0, crossings = 0;
  std::string crsName;
};
DpSummary runDpJob(const std::string& inPath, const std::string& outPath, const DpOptions& options, bool overwrite,
                   const Feedback& feedback);

// `tinlod lines concavity`: per vertex the secant measure (window d along the line) and
// the disk measure (radius r), as layer 'vertices' (Point: line, vertex, secant, disk;
// null where undefined), and the lines cut into convex, straight and concave parts by the
// secant measure (layer 'parts': feature, class).
struct ConcavityOptions {
  double window = 0;          // metres along the line; or, with windowFraction, ...
  double windowFraction = 0;  // ... this share of each line's length (for simplified lines)
  double radius = 0;          // the disk's; 0: the window
  double threshold = 0.02;    // |secant| above it: convex or concave
  void validate() const;      // throws Error naming the option
};
struct ConcavitySummary {
  std::size_t lines = 0, vertices = 0, convex = 0, straight = 0, concave = 0;  // parts by class
  std::string crsName;
};
ConcavitySummary runConcavityJob(const std::string& inPath, const std::string& outPath, const ConcavityOptions& options,
                                 bool overwrite, const Feedback& feedback);

}  // namespace tinlod
