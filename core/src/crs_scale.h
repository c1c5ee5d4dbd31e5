// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <string>
#include <vector>

namespace tinlod {

struct LonLat {
  double lon = 0, lat = 0;  // degrees
};

// How far a projected CRS's scale strays from 1 at the points, from PROJ's scale factors:
// the larger of the meridional and parallel errors (0.27 for Web Mercator at San Francisco,
// 0.001 at the edge of a UTM zone). NaN when PROJ cannot tell: no projected CRS, or a point
// it cannot project.
double worstScaleError(const std::string& crsDefinition, const std::vector<LonLat>& points);

// A CRS for a DEM whose points a UTM zone stretches too much: the conformal one, among a
// transverse Mercator, a Lambert conic, a Mercator and a polar stereographic centred on
// the DEM, that strays least from true scale at the points, its scale factor chosen so
// that it shrinks as much as it stretches.
struct FittedCrs {
  std::string definition;  // a PROJ string, as -t_srs takes it
  std::string kind;        // "a Lambert conformal conic", for messages
  double error = 0;        // worstScaleError at the points; infinity when none holds them all
};
FittedCrs fittedCrs(const std::vector<LonLat>& points, LonLat centre);

// A scale error for messages: "12 %", "0.2 %", "1.04 %" (never "1 %" for one over 1 %).
std::string percentText(double fraction);

// What to do about a CRS that stretches a DEM by `error` (at least 1 %): the UTM zone of its
// centre when that keeps within 1 %, else the CRS fittedCrs finds, or the news that none of
// those keeps a DEM this large within 1 %. Worded for -t_srs.
std::string scaleAdvice(const std::vector<LonLat>& points, LonLat centre, double error);

// What to use for a DEM that a CRS cannot project whole (a hemisphere in one UTM zone): the
// CRS fittedCrs finds, which covers every point, with its scale error (and, over 5 %, the
// advice to cut the DEM into regions), or the news that none of those covers a DEM this large
// within 50 %. Worded for -t_srs.
std::string coverAdvice(const std::vector<LonLat>& points, LonLat centre);

}  // namespace tinlod
