// SPDX-License-Identifier: GPL-3.0-or-later
#include "gpkg_output.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "gdal_metadata_xml.h"
#include "gpkg_spatial_index.h"
#include "sqlite_in_use.h"
#include "text_and_paths.h"
#include "tinlod/error.h"

namespace fs = std::filesystem;

namespace tinlod {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

// GDAL's own messages would print the temporary file's name: they are kept quiet and
// the caller words the error in terms of the user's file.
GDALDataset* openOrCreate(const fs::path& tmp, bool fromCopy) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GPKG");
  if (!driver) throw Error("GDAL was built without the GeoPackage driver");
  CPLPushErrorHandler(CPLQuietErrorHandler);
  // GDAL makes a new GeoPackage in some twenty transactions, each making and removing a
  // journal file. The file is a staged copy, thrown away on failure: the journal stays in
  // memory, where GDAL's own rollbacks still find it.
  CPLSetThreadLocalConfigOption("OGR_SQLITE_JOURNAL", "MEMORY");
  // 16 KiB pages hold 13 R-tree nodes where 4 KiB ones hold 3 with a tenth left empty, and
  // waste less at the end of each page of rows: 7 bytes a triangle less than GDAL's 4 KiB.
  // GDAL sets it before its first table; a file that has the user's layers keeps its own.
  if (!fromCopy) CPLSetThreadLocalConfigOption("OGR_SQLITE_PRAGMA", "page_size=16384");
  const char* const gpkgOnly[] = {"GPKG", nullptr};
  GDALDataset* ds = fromCopy ? static_cast<GDALDataset*>(GDALOpenEx(tmp.c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE,
                                                                    gpkgOnly, nullptr, nullptr))
                             : driver->Create(tmp.c_str(), 0, 0, 0, GDT_Unknown, nullptr);
  CPLSetThreadLocalConfigOption("OGR_SQLITE_JOURNAL", nullptr);
  CPLSetThreadLocalConfigOption("OGR_SQLITE_PRAGMA", nullptr);
  CPLPopErrorHandler();
  return ds;
}

// The outputs whose layers replace each other's: a TIN, a hierarchy and a level-of-detail
// TIN share theirs (isTinlodLayer); each other kind has its own.
std::string familyOf(const std::string& kind) {
  return kind == "tin" || kind == "hierarchy" || kind == "lod" ? "tin" : kind;
}

// -overwrite replaces the layers of the output being written and keeps a GeoPackage's other
// layers: into a tinlod file of another kind (a TIN given as a lines job's output), that
// would leave the old kind's layers under the new kind's metadata, a file neither reads.
// Returns the kind the file holds ("" for none).
std::string refuseAnotherKind(const std::string& path, const GpkgWriteOptions& options) {
  const auto given = options.metadata.find("TINLOD_KIND");
  const std::string kind = given == options.metadata.end() ? "" : given->second;
  GDALAllRegister();
  CPLPushErrorHandler(CPLQuietErrorHandler);
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  CPLPopErrorHandler();
  const char* old = ds ? ds->GetMetadataItem("TINLOD_KIND") : nullptr;
  if (!old || kind.empty() || familyOf(old) == familyOf(kind)) return old ? old : "";
  throw Error("'" + path + "' holds a tinlod " + old + " output: -overwrite replaces the layers of the same kind " +
              "of output and keeps the others, so writing " + kind + " into it would leave a file of two kinds that " +
              "neither reads; name another file, or remove this one first");
}

// An existing output is updated (its other layers kept): one GDAL cannot open as a
// GeoPackage would fail only when the job writes, after the long work.
void refuseNonGeoPackage(const std::string& path) {
  GDALAllRegister();
  const char* const gpkgOnly[] = {"GPKG", nullptr};
  CPLPushErrorHandler(CPLQuietErrorHandler);
  // A GeoPackage of rasters only is one too (the DEM itself, named as the output, is then
  // refused as an input of the run).
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_RASTER | GDAL_OF_READONLY, gpkgOnly));
  CPLPopErrorHandler();
  if (!ds) throw Error("output '" + path + "' exists but is not a GeoPackage GDAL can update: remove it or choose another name");
}

}  // namespace

void warnOfReplacedKind(const std::string& path, const std::string& held, const GpkgWriteOptions& options,
                        const ProgressRange& progress) {
  const auto given = options.metadata.find("TINLOD_KIND");
  if (held.empty() || given == options.metadata.end() || held == given->second) return;
  const auto words = [](const std::string& kind) {
    return kind == "hierarchy" ? std::string("TIN hierarchy") : kind == "lod" ? std::string("level-of-detail TIN") : "TIN";
  };
  progress.warn("'" + path + "' held a tinlod " + words(held) +
                (held == "hierarchy" ? " (its levels, groups and level views)" : "") + ": this run's " +
                words(given->second) + " will replace it, its other layers kept");
}

std::string checkOutputPath(const std::string& path, const GpkgWriteOptions& options) {
  refuseVirtualPath(path, "output");
  const fs::path out(path);
  if (lower(out.extension().string()) != ".gpkg")
    throw Error("output '" + path + "' must be a GeoPackage file ending in .gpkg");
  const fs::path dir = out.parent_path().empty() ? fs::path(".") : out.parent_path();
  if (!fs::is_directory(dir)) throw Error("the folder of output '" + path + "' does not exist" + tildeHint(path));
  if (access(dir.c_str(), W_OK) != 0) throw Error("the folder of output '" + path + "' is not writable");
  if (fs::is_directory(out)) throw Error("output '" + path + "' is a folder: name a .gpkg file");
  if (!fs::exists(out)) return "";
  if (const std::string held = sqliteFileInUse(out); !held.empty())
    throw Error("output '" + path + "' " + held + ": close it there, then run again");
  refuseNonGeoPackage(path);
  std::string held = refuseAnotherKind(path, options);  // first: -overwrite would not help
  if (!options.overwrite)
    throw Error("output '" + path + "' exists: add -overwrite to replace its tinlod layers (its other layers are kept)");
  return held;
}

bool isTinlodLayer(const std::string& name) {
  if (name == "vertices" || name == "triangles" || name == "groups" || name == "levels") return true;
  if (name.rfind("level_", 0) != 0 || name.size() == 6) return false;
  return std::all_of(name.begin() + 6, name.end(), [](unsigned char c) { return std::isdigit(c); });
}

void writeFeature(OGRLayer& layer, OGRFeature& feature) {
  if (layer.CreateFeature(&feature) != OGRERR_NONE)
    throw Error(std::string("cannot write to layer '") + layer.GetName() + "': " + CPLGetLastErrorMsg());
}

GpkgOutput::GpkgOutput(const StagedFile& file, const GpkgWriteOptions& options,
                       std::function<bool(const std::string&)> ours)
    : file_(file), options_(options) {
  // A file of ours alone is replaced by a new one: faster than copying it, dropping its
  // layers and compacting what they leave (a rewrite of the whole file without a word of
  // progress). One with other content is copied and updated.
  if (file_.existed && file_.keepContent && fs::exists(file_.target)) refuseAnotherKind(file_.path, options_);  // checked again: it may have changed
  const bool update = file_.existed && file_.keepContent && fs::exists(file_.target) && !holdsOnly(file_.target, ours);
  if (update) copyForUpdate(file_);
  ds_ = openOrCreate(file_.staging, update);
  if (!ds_)
    throw Error(update ? "'" + file_.path + "' exists but is not a GeoPackage GDAL can update: remove it or choose another name"
                       : "cannot create GeoPackage '" + file_.path + "': " + said(CPLGetLastErrorMsg()));
  if (update) dropOurs(ours);
}

bool GpkgOutput::holdsOnly(const fs::path& path, const std::function<bool(const std::string&)>& ours) {
  GDALAllRegister();
  const char* const gpkgOnly[] = {"GPKG", nullptr};
  CPLPushErrorHandler(CPLQuietErrorHandler);
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, gpkgOnly));
  CPLPopErrorHandler();
  if (!ds) return false;  // not a GeoPackage: the update says so
  // Every table and view, registered or not (QGIS keeps projects in a plain table), must be
  // the GeoPackage's own, an index's, or the job's; and the metadata only the job's items.
  std::vector<std::string> names;
  // A GeoPackage without metadata (ogr2ogr's) has no gpkg_metadata table: GDAL printed
  // "ERROR 1: ... no such table" on a run that went well.
  CPLPushErrorHandler(CPLQuietErrorHandler);
  if (OGRLayer* r = ds->ExecuteSQL("SELECT name FROM sqlite_master WHERE type IN ('table', 'view') "
                                   "UNION ALL SELECT 'metadata:' || count(*) FROM gpkg_metadata "
                                   "UNION ALL SELECT 'domains:' || count(*) FROM gpkg_metadata WHERE metadata LIKE '%domain=%'",
                                   nullptr, nullptr)) {
    for (auto& f : *r) names.push_back(f->GetFieldAsString(0));
    ds->ReleaseResultSet(r);
  }
  CPLPopErrorHandler();
  if (names.empty()) return false;  // no gpkg_metadata table, or unreadable: keep what is there
  const auto infrastructure = [](const std::string& name) {
    return name.rfind("gpkg_", 0) == 0 || name.rfind("rtree_", 0) == 0 || name.rfind("sqlite_", 0) == 0;
  };
  for (const std::string& name : names) {
    if (name == "metadata:0" || name == "metadata:1" || name == "domains:0") continue;
    if (name.rfind("metadata:", 0) == 0 || name.rfind("domains:", 0) == 0) return false;
    if (!infrastructure(name) && !ours(name)) return false;
  }
  for (char** item = ds->GetMetadata(); item && *item; ++item)
    if (std::string(*item).rfind("TINLOD_", 0) != 0) return false;
  return true;
}

GpkgOutput::~GpkgOutput() {
  abandonIndexes_->store(true);  // first: a cancelled write waited up to 2 s for them (alps_2x2)
  if (!ds_) return;
  // Closing after a failure or a cancel: GDAL's complaints (an R-tree thread cut short)
  // would only confuse; the temporary file is removed anyway.
  CPLPushErrorHandler(CPLQuietErrorHandler);
  GDALClose(ds_);
  CPLPopErrorHandler();
}

void GpkgOutput::dropOurs(const std::function<bool(const std::string&)>& ours) {
  // Views first: GDAL lists them as layers but cannot drop them, and a view dropped by SQL
  // under GDAL's layer object for it makes closing fail. So they go by SQL, and the file
  // is reopened before the tables go through GDAL.
  std::vector<std::string> views;
  if (OGRLayer* r = ds_->ExecuteSQL("SELECT name FROM sqlite_master WHERE type = 'view'", nullptr, nullptr)) {
    for (auto& f : *r) views.push_back(f->GetFieldAsString(0));
    ds_->ReleaseResultSet(r);
  }
  bool dropped = false;
  for (const std::string& v : views)
    if (ours(v)) {
      execute("DROP VIEW \"" + v + "\"");
      execute("DELETE FROM gpkg_geometry_columns WHERE table_name = " + quoted(v));
      execute("DELETE FROM gpkg_contents WHERE table_name = " + quoted(v));
      dropped = true;
    }
  if (dropped) {
    CPLPushErrorHandler(CPLQuietErrorHandler);
    GDALClose(ds_);
    CPLPopErrorHandler();
    ds_ = openOrCreate(file_.staging, true);
    if (!ds_) throw Error("cannot reopen '" + file_.path + "' to update it");
  }
  for (int i = ds_->GetLayerCount() - 1; i >= 0; --i) {
    const std::string name = ds_->GetLayer(i)->GetName();
    if (ours(name)) {
      if (ds_->DeleteLayer(i) != OGRERR_NONE) throw Error("cannot replace layer '" + name + "' of '" + file_.path + "'");
      dropped = true;
    }
  }
  vacuum_ = dropped;  // what was dropped leaves free pages: compact the file at the end
}

OGRLayer* GpkgOutput::createLayer(const char* name, OGRwkbGeometryType type, const std::string& crsWkt,
                                  const std::vector<FieldSpec>& fields, bool bulk) {
  OGRSpatialReference srs;
  OGRSpatialReference* srsPtr = nullptr;
  if (type != wkbNone && !crsWkt.empty() && srs.importFromWkt(crsWkt.c_str()) == OGRERR_NONE) srsPtr = &srs;
  // The bulk writer names the columns fid and geom itself: GDAL's defaults, made explicit.
  const char* const bulkOptions[] = {"SPATIAL_INDEX=NO", "FID=fid", "GEOMETRY_NAME=geom", nullptr};
  CPLErrorReset();
  OGRLayer* layer = nullptr;
  {
    const CPLErrorHandlerPusher quiet(CPLQuietErrorHandler);  // said below, in the user's terms
    layer = ds_->CreateLayer(name, srsPtr, type, bulk ? const_cast<char**>(bulkOptions) : nullptr);
  }
  if (!layer || CPLGetLastErrorType() >= CE_Failure) throw Error(std::string("cannot create layer '") + name + "' in '" + file_.path + "': " + said(CPLGetLastErrorMsg()));
  if (bulk && type != wkbNone && !srsPtr) withoutCrs_.push_back(name);
  for (const FieldSpec& field : fields) {
    OGRFieldDefn defn(field.name, field.type);
    defn.SetSubType(field.subType);
    if (layer->CreateField(&defn) != OGRERR_NONE) throw Error(std::string("cannot create field ") + field.name);
  }
  return layer;
}

void GpkgOutput::execute(const std::string& sql) {
  CPLErrorReset();
  OGRLayer* result = ds_->ExecuteSQL(sql.c_str(), nullptr, nullptr);
  if (result) ds_->ReleaseResultSet(result);
  if (CPLGetLastErrorType() >= CE_Failure) throw Error("GeoPackage statement on '" + file_.path + "' failed: " + said(CPLGetLastErrorMsg()));
}

void GpkgOutput::createFeatureView(const std::string& name, const std::string& select, const std::string& baseTable,
                                   const std::string& description) {
  SqliteDatabase& db = database();
  db.execute("CREATE VIEW \"" + name + "\" AS " + select);
  db.execute("INSERT INTO gpkg_contents (table_name, data_type, identifier, description, srs_id) SELECT " + quoted(name) +
             ", 'features', " + quoted(name) + ", " + quoted(description) + ", srs_id FROM gpkg_contents WHERE table_name = " +
             quoted(baseTable));
  db.execute("INSERT INTO gpkg_geometry_columns (table_name, column_name, geometry_type_name, srs_id, z, m) SELECT " +
             quoted(name) + ", column_name, geometry_type_name, srs_id, z, m FROM gpkg_geometry_columns WHERE table_name = " +
             quoted(baseTable));
}

SqliteDatabase& GpkgOutput::database() {
  if (db_) return *db_;
  writeMetadata(false);  // the late items are written once the rows are in
  closeGdal();
  db_ = std::make_unique<SqliteDatabase>(file_.staging.string(), file_.path);
  db_->execute("BEGIN");
  // GDAL gives a layer without a CRS srs_id 0, the undefined geographic CRS, which GDAL and
  // QGIS read back as degrees; a TIN in no CRS is Cartesian: -1. (Bulk layers only: GDAL
  // stamps the rows it writes itself with the layer's srs_id.)
  for (const std::string& table : withoutCrs_)
    for (const char* registry : {"gpkg_geometry_columns", "gpkg_contents"})
      db_->execute(std::string("UPDATE ") + registry + " SET srs_id = -1 WHERE lower(table_name) = lower(" + quoted(table) + ")");
  return *db_;
}

std::int32_t GpkgOutput::srsId(const std::string& table) {
  SqliteStatement srs = database().prepare("SELECT srs_id FROM gpkg_geometry_columns WHERE lower(table_name) = lower(?)");
  srs.bindText(1, table);
  if (!srs.step()) throw Error("layer '" + table + "' of '" + file_.path + "' has no geometry column");
  const auto id = static_cast<std::int32_t>(srs.integerColumn(0));
  srs.reset();
  return id;
}

void GpkgOutput::indexLater(const std::string& table, std::function<std::vector<RtreeBox>()> boxes) {
  const int capacity = gpkgRtreeCapacity(database());
  std::shared_future<std::shared_ptr<PackedRtree>> previous;
  if (!indexes_.empty()) previous = indexes_.back().tree;
  // One packing at a time, in the order asked: the caller's thread writes rows on the
  // other core, and only one layer's boxes are held at once.
  auto pack = [previous, boxes = std::move(boxes), capacity, abandon = abandonIndexes_]() -> std::shared_ptr<PackedRtree> {
    if (previous.valid()) previous.wait();
    if (abandon->load()) return nullptr;
    try {
      return std::make_shared<PackedRtree>(boxes(), capacity, abandon.get());
    } catch (const PackingAbandoned&) {
      return nullptr;
    }
  };
  indexes_.push_back({table, std::async(std::launch::async, std::move(pack)).share()});
}

namespace {

// The pages of dropped layers are reused by the rows written after them: compacting, a
// rewrite of the whole file that reports no progress, pays only when many are left over
// (a smaller output than the one it replaces).
void compactIfWasteful(SqliteDatabase& db) {
  const std::int64_t pages = db.integer("PRAGMA page_count"), unused = db.integer("PRAGMA freelist_count");
  if (unused * 8 > pages) db.execute("VACUUM");  // outside any transaction, as SQLite requires
}

}  // namespace

void GpkgOutput::compactIfDropped() {
  if (!vacuum_) return;
  SqliteDatabase db(file_.staging.string(), file_.path);
  compactIfWasteful(db);
}

void GpkgOutput::begin() {
  if (ds_->StartTransaction() != OGRERR_NONE) throw Error("cannot start a GeoPackage transaction");
}

void GpkgOutput::commit() {
  if (ds_->CommitTransaction() != OGRERR_NONE) throw Error("cannot commit to GeoPackage '" + file_.path + "'");
}

void GpkgOutput::writeMetadata(bool withLate) {
  // The file's own TINLOD_* items are replaced as a set (a sample written over a hierarchy
  // must not keep the hierarchy's); other items are kept.
  CPLStringList metadata;
  for (char** item = ds_->GetMetadata(); item && *item; ++item)
    if (std::string(*item).rfind("TINLOD_", 0) != 0) metadata.AddString(*item);
  for (const auto& [key, value] : options_.metadata) metadata.SetNameValue(key.c_str(), value.c_str());
  if (withLate && options_.lateMetadata)
    for (const auto& [key, value] : options_.lateMetadata()) metadata.SetNameValue(key.c_str(), value.c_str());
  ds_->SetMetadata(metadata.List());
}

void GpkgOutput::closeGdal() {
  // GDAL 3.6's GDALClose returns nothing: a failed final write shows as a CPL error.
  CPLErrorReset();
  GDALClose(ds_);
  ds_ = nullptr;
  if (CPLGetLastErrorType() >= CE_Failure)
    throw Error("cannot finish GeoPackage '" + file_.path + "': " + said(CPLGetLastErrorMsg()));
}

void GpkgOutput::finishDatabase(const ProgressRange& progress) {
  double total = 0, done = 0;
  for (const PendingIndex& index : indexes_) total += double(index.tree.get()->entries()) + 1;
  for (PendingIndex& index : indexes_) {
    // Each tree's memory goes back as soon as it is written, before the next one's.
    PackedRtree& tree = *index.tree.get();
    const double share = (double(tree.entries()) + 1) / total;
    writeGpkgSpatialIndex(*db_, index.table, std::move(tree), progress.sub(0.95 * done, 0.95 * (done + share)));
    done += share;
  }
  indexes_.clear();
  const bool lateWritten = options_.lateMetadata && setGdalMetadataItems(*db_, options_.lateMetadata());
  db_->execute("COMMIT");
  if (vacuum_) compactIfWasteful(*db_);
  db_.reset();
  if (options_.lateMetadata && !lateWritten) {
    // No metadata of GDAL's to add to: GDAL writes the late items itself.
    ds_ = openOrCreate(file_.staging, true);
    if (!ds_) throw Error("cannot reopen GeoPackage '" + file_.path + "' to finish it");
    for (const auto& [key, value] : options_.lateMetadata()) ds_->SetMetadataItem(key.c_str(), value.c_str());
    closeGdal();
  }
}

void GpkgOutput::finish(const ProgressRange& progress) {
  if (db_) {
    finishDatabase(progress);
  } else {
    writeMetadata(true);
    progress.report(0, "Building the spatial index");
    closeGdal();  // GDAL builds its layers' spatial indexes here
    compactIfDropped();
  }
  // Nothing is in place before the job commits its outputs: a cancel asked for during the
  // index build is still honoured here. (The end of the range, 1, is the job's to report
  // once the file is in place, when a cancel comes too late.)
  progress.report(0.99, "Finishing the GeoPackage");
}

}  // namespace tinlod
