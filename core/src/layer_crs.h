// SPDX-License-Identifier: GPL-3.0-or-later
// Private: a vector layer's CRS as tinlod reads it. GDAL/OGR stays in the I/O files.
#pragma once

#include <ogrsf_frmts.h>

#include <string>

namespace tinlod {

// The layer's CRS; none for the GeoPackage's two undefined ones (srs_id 0 and -1), which
// GDAL reads back as a geographic and a Cartesian CRS: a TIN written without a CRS is in
// no CRS, not in degrees.
const OGRSpatialReference* layerCrs(OGRLayer& layer);

// A CRS's name for people: its own, or for a CRS made from a PROJ string (named "unknown"
// by PROJ), that string.
std::string crsLabel(const OGRSpatialReference& srs);

}  // namespace tinlod
