// SPDX-License-Identifier: GPL-3.0-or-later
// Damaging tinlod GeoPackages on purpose, through SQLite itself, as anyone could with the
// sqlite3 shell: the readers must take whatever a file holds as data to check.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace tinlod::test {

// A hierarchy of a small synthetic DEM (60 x 50 cells of 25 m: some 550 vertices and 15
// levels), built once per test binary by tinlod's own build job; the DEM as a GeoTIFF;
// and a point layer of a few of its vertices (in its CRS) for locate.
struct SmallHierarchy {
  std::string dem, gpkg, points;
};
const SmallHierarchy& smallHierarchy();

// Runs `sql` on a GeoPackage through SQLite; SQLite's error message, empty on success.
std::string runSql(const std::string& gpkg, const std::string& sql);

// One integer SQLite gives for `sql` (the first column of the first row), or -1.
long long sqlInteger(const std::string& gpkg, const std::string& sql);

// A copy of `gpkg` in a fresh file. Its R-tree triggers are dropped: they call functions
// only GDAL defines (ST_IsEmpty ...), so that SQLite alone could change no row of a table
// with a geometry. The readers do not use the R-trees.
std::string editableCopy(const std::string& gpkg);

// An editable copy changed by `sql`; the test fails when SQLite refuses it.
std::string alteredCopy(const std::string& gpkg, const std::string& sql);

// Sets a TINLOD_ item of the file's metadata (GDAL keeps it as XML in gpkg_metadata);
// false when the file has no such item.
bool setTinlodItem(const std::string& gpkg, const std::string& key, const std::string& value);

// An SQL literal of a GeoPackage point blob (little-endian WKB, no envelope) at (x, y, z).
std::string pointBlobLiteral(double x, double y, double z, int srsId);

// Writes a vector layer of one geometry per WKT text (in EPSG:32632) to a new file.
void writeWktLayer(const std::string& path, const std::vector<std::string>& wkts);

}  // namespace tinlod::test
