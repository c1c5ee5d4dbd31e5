// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the files behind a dataset a job reads, so that no output replaces one of them.
#pragma once

#include <string>
#include <vector>

namespace tinlod {

// The file of `spec` (a path, or "file.gpkg|layername=x") and every file GDAL reads with it
// (an ENVI .hdr, a shapefile's .dbf, .aux.xml); just the file when GDAL cannot open it
// (its reader will say why).
std::vector<std::string> datasetFiles(const std::string& spec);

// datasetFiles of each path, together.
std::vector<std::string> datasetFiles(const std::vector<std::string>& paths);

}  // namespace tinlod
