// SPDX-License-Identifier: GPL-3.0-or-later
// Private: small helpers the core's messages and checks share.
#pragma once

#include <string>

namespace tinlod {

// A number as a person writes it: 0.99, 20, 1e-05 (not 0.990000).
std::string formatNumber(double value);

// `text` as a quoted JSON string, escaped.
std::string jsonString(const std::string& text);

// True when `path` is a plain file path (not /vsi..., not DRIVER:...) that does not
// exist: said plainly before GDAL would answer with its own wording.
bool plainPathMissing(const std::string& path);

// For a message on a path that does not exist: a path starting with ~ was quoted where a
// shell would have expanded it (a script's "~/dem.tif"), which tinlod does not.
std::string tildeHint(const std::string& path);

// A DEM's path as an output records it: a plain file's absolute, so that it names the same
// file from any folder (tinlod accuracy takes the build's -s_srs for that DEM); GDAL's other
// names (/vsizip/..., NETCDF:"f.nc":z) as given.
std::string recordedPath(const std::string& path);

}  // namespace tinlod
