// SPDX-License-Identifier: GPL-3.0-or-later
#include "gpkg_surgery.h"

#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>
#include <sqlite3.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <regex>

#include "test_support.h"
#include "tinlod/build_job.h"
#include "tinlod/synthetic_dem.h"

namespace fs = std::filesystem;

namespace tinlod::test {
namespace {

struct SqliteCloser {
  void operator()(sqlite3* db) const { sqlite3_close(db); }
};
using Database = std::unique_ptr<sqlite3, SqliteCloser>;

Database openDatabase(const std::string& gpkg) {
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(gpkg.c_str(), &db, SQLITE_OPEN_READWRITE, nullptr) != SQLITE_OK) {
    sqlite3_close(db);
    return nullptr;
  }
  // Copies made to be damaged need no protection from power loss: no disk syncs.
  sqlite3_exec(db, "PRAGMA synchronous = OFF", nullptr, nullptr, nullptr);
  return Database(db);
}

// Every fifth vertex of the hierarchy: points on the TIN at level 0.
std::vector<std::string> someVertices(const std::string& gpkg) {
  std::vector<std::string> wkts;
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpenEx(gpkg.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
  if (!ds) return wkts;
  for (auto& f : *ds->GetLayerByName("vertices"))
    if (f->GetFID() % 5 == 0) wkts.push_back(f->GetGeometryRef()->exportToWkt());
  GDALClose(ds);
  return wkts;
}

SmallHierarchy makeSmallHierarchy() {
  SmallHierarchy s;
  const std::string dir = tempDir();
  SyntheticDemOptions o;
  o.width = 60, o.height = 50, o.cellSize = 25;
  s.dem = dir + "/dem.tif", s.gpkg = dir + "/h.gpkg", s.points = dir + "/points.gpkg";
  writeDemGeoTiff(makeSyntheticDem(o), s.dem);
  runBuildJob(s.dem, s.gpkg, {}, {}, false, {});
  writeWktLayer(s.points, someVertices(s.gpkg));
  return s;
}

std::string xmlEscaped(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '&' ? "&amp;" : c == '<' ? "&lt;" : c == '>' ? "&gt;" : std::string(1, c);
  return out;
}

}  // namespace

const SmallHierarchy& smallHierarchy() {
  static const SmallHierarchy s = makeSmallHierarchy();
  return s;
}

std::string runSql(const std::string& gpkg, const std::string& sql) {
  const Database db = openDatabase(gpkg);
  if (!db) return "cannot open " + gpkg;
  char* message = nullptr;
  if (sqlite3_exec(db.get(), sql.c_str(), nullptr, nullptr, &message) == SQLITE_OK) return "";
  std::string out = message ? message : "SQLite error";
  sqlite3_free(message);
  return out;
}

long long sqlInteger(const std::string& gpkg, const std::string& sql) {
  const Database db = openDatabase(gpkg);
  sqlite3_stmt* statement = nullptr;
  if (!db || sqlite3_prepare_v2(db.get(), sql.c_str(), -1, &statement, nullptr) != SQLITE_OK) return -1;
  const long long value = sqlite3_step(statement) == SQLITE_ROW ? sqlite3_column_int64(statement, 0) : -1;
  sqlite3_finalize(statement);
  return value;
}

std::string editableCopy(const std::string& gpkg) {
  static int counter = 0;
  static const std::string dir = tempDir();
  const std::string copy = dir + "/copy" + std::to_string(++counter) + ".gpkg";
  fs::copy_file(gpkg, copy);
  std::string drops;
  const Database db = openDatabase(copy);
  sqlite3_stmt* statement = nullptr;
  sqlite3_prepare_v2(db.get(), "SELECT name FROM sqlite_master WHERE type = 'trigger' AND name LIKE 'rtree%'", -1,
                     &statement, nullptr);
  while (sqlite3_step(statement) == SQLITE_ROW)
    drops += "DROP TRIGGER \"" + std::string(reinterpret_cast<const char*>(sqlite3_column_text(statement, 0))) + "\";";
  sqlite3_finalize(statement);
  EXPECT_EQ(sqlite3_exec(db.get(), drops.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
  return copy;
}

std::string alteredCopy(const std::string& gpkg, const std::string& sql) {
  const std::string copy = editableCopy(gpkg);
  EXPECT_EQ(runSql(copy, sql), "") << sql;
  return copy;
}

bool setTinlodItem(const std::string& gpkg, const std::string& key, const std::string& value) {
  const Database db = openDatabase(gpkg);
  sqlite3_stmt* read = nullptr;
  if (!db || sqlite3_prepare_v2(db.get(), "SELECT id, metadata FROM gpkg_metadata", -1, &read, nullptr) != SQLITE_OK)
    return false;
  const bool found = sqlite3_step(read) == SQLITE_ROW && sqlite3_column_text(read, 1);
  const long long id = found ? sqlite3_column_int64(read, 0) : 0;
  const std::string xml = found ? reinterpret_cast<const char*>(sqlite3_column_text(read, 1)) : "";
  sqlite3_finalize(read);
  const std::regex item("<MDI key=\"TINLOD_" + key + "\">[^<]*</MDI>");
  if (!std::regex_search(xml, item)) return false;
  const std::string changed =
      std::regex_replace(xml, item, "<MDI key=\"TINLOD_" + key + "\">" + xmlEscaped(value) + "</MDI>");
  sqlite3_stmt* write = nullptr;
  sqlite3_prepare_v2(db.get(), "UPDATE gpkg_metadata SET metadata = ? WHERE id = ?", -1, &write, nullptr);
  sqlite3_bind_text(write, 1, changed.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_int64(write, 2, id);
  const bool written = sqlite3_step(write) == SQLITE_DONE;
  sqlite3_finalize(write);
  return written;
}

std::string pointBlobLiteral(double x, double y, double z, int srsId) {
  std::string bytes = {'G', 'P', 0, 1};  // magic, version 0, flags: little endian, no envelope
  auto append = [&bytes](const void* p, std::size_t n) { bytes.append(static_cast<const char*>(p), n); };
  const std::int32_t srs = srsId;
  const std::uint32_t pointZ = 1001;
  append(&srs, 4);
  bytes += '\1';  // WKB little endian
  append(&pointZ, 4);
  for (double v : {x, y, z}) append(&v, 8);
  std::string hex = "X'";
  char digits[3];
  for (unsigned char c : bytes) std::snprintf(digits, sizeof digits, "%02X", c), hex += digits;
  return hex + "'";
}

void writeWktLayer(const std::string& path, const std::vector<std::string>& wkts) {
  GDALAllRegister();
  OGRSpatialReference srs;
  srs.importFromEPSG(32632);
  std::vector<OGRGeometry*> geometries;
  for (const std::string& wkt : wkts) {
    OGRGeometry* g = nullptr;
    ASSERT_EQ(OGRGeometryFactory::createFromWkt(wkt.c_str(), &srs, &g), OGRERR_NONE) << wkt;
    geometries.push_back(g);
  }
  // The layer declares the one type of its geometries, as a file of one kind would.
  OGRwkbGeometryType type = geometries.empty() ? wkbUnknown : geometries.front()->getGeometryType();
  for (const OGRGeometry* g : geometries)
    if (g->getGeometryType() != type) type = wkbUnknown;
  GDALDataset* ds =
      GetGDALDriverManager()->GetDriverByName("GPKG")->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr);
  ASSERT_NE(ds, nullptr) << path;
  OGRLayer* layer = ds->CreateLayer("features", &srs, type, nullptr);
  for (OGRGeometry* g : geometries) {
    OGRFeature f(layer->GetLayerDefn());
    f.SetGeometryDirectly(g);
    EXPECT_EQ(layer->CreateFeature(&f), OGRERR_NONE);
  }
  GDALClose(ds);
}

}  // namespace tinlod::test
