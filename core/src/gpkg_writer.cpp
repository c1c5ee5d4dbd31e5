// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/gpkg_writer.h"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "temporary_output.h"
#include "tinlod/error.h"

namespace fs = std::filesystem;

namespace tinlod {
namespace {

const char* const kLayerNames[] = {"vertices", "triangles"};

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// GDAL's own messages would print the temporary file's name: they are kept quiet and
// the caller words the error in terms of the user's file.
GDALDataset* openOrCreate(const fs::path& tmp, bool fromCopy) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GPKG");
  if (!driver) throw Error("GDAL was built without the GeoPackage driver");
  CPLPushErrorHandler(CPLQuietErrorHandler);
  const char* const gpkgOnly[] = {"GPKG", nullptr};
  GDALDataset* ds = fromCopy ? static_cast<GDALDataset*>(GDALOpenEx(tmp.c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE,
                                                                    gpkgOnly, nullptr, nullptr))
                             : driver->Create(tmp.c_str(), 0, 0, 0, GDT_Unknown, nullptr);
  CPLPopErrorHandler();
  return ds;
}

void deleteOurLayers(GDALDataset& ds) {
  for (int i = ds.GetLayerCount() - 1; i >= 0; --i) {
    const std::string name = ds.GetLayer(i)->GetName();
    if (std::find(std::begin(kLayerNames), std::end(kLayerNames), name) != std::end(kLayerNames))
      if (ds.DeleteLayer(i) != OGRERR_NONE) throw Error("cannot replace layer '" + name + "'");
  }
}

OGRLayer* createLayer(GDALDataset& ds, const char* name, OGRwkbGeometryType type,
                      OGRSpatialReference* srs, const std::vector<std::string>& intFields) {
  OGRLayer* layer = ds.CreateLayer(name, srs, type, nullptr);
  if (!layer) throw Error(std::string("cannot create layer '") + name + "': " + CPLGetLastErrorMsg());
  for (const std::string& field : intFields) {
    OGRFieldDefn defn(field.c_str(), OFTInteger);
    if (field == "outline") defn.SetSubType(OFSTBoolean);
    if (layer->CreateField(&defn) != OGRERR_NONE) throw Error("cannot create field " + field);
  }
  return layer;
}

void writeFeature(OGRLayer& layer, OGRFeature& feature) {
  if (layer.CreateFeature(&feature) != OGRERR_NONE)
    throw Error(std::string("cannot write to layer '") + layer.GetName() + "': " + CPLGetLastErrorMsg());
}

void writeVertices(const Tin& tin, OGRLayer& layer, const ProgressRange& progress) {
  OGRFeature feature(layer.GetLayerDefn());
  for (std::size_t i = 0; i < tin.vertices.size(); ++i) {
    const TinVertex& v = tin.vertices[i];
    feature.SetFID(static_cast<GIntBig>(i) + 1);
    feature.SetField(0, static_cast<int>(i) + 1);
    feature.SetField(1, v.row);
    feature.SetField(2, v.col);
    feature.SetField(3, v.outline ? 1 : 0);
    feature.SetGeometryDirectly(new OGRPoint(v.x, v.y, v.z));
    writeFeature(layer, feature);
    if ((i & 0x3FFF) == 0) progress.report(double(i) / tin.vertices.size(), "Writing vertices");
  }
}

void writeTriangles(const Tin& tin, OGRLayer& layer, const ProgressRange& progress) {
  OGRFeature feature(layer.GetLayerDefn());
  for (std::size_t i = 0; i < tin.triangles.size(); ++i) {
    const Triangle& t = tin.triangles[i];
    auto* ring = new OGRLinearRing();
    ring->setNumPoints(4);
    for (int k = 0; k < 4; ++k) {
      const TinVertex& v = tin.vertices[t[k % 3]];
      ring->setPoint(k, v.x, v.y, v.z);
    }
    auto* polygon = new OGRPolygon();
    polygon->addRingDirectly(ring);
    feature.SetFID(static_cast<GIntBig>(i) + 1);
    feature.SetField(0, static_cast<int>(i) + 1);
    for (int k = 0; k < 3; ++k) feature.SetField(k + 1, static_cast<int>(t[k]) + 1);
    feature.SetGeometryDirectly(polygon);
    writeFeature(layer, feature);
    if ((i & 0x3FFF) == 0) progress.report(double(i) / tin.triangles.size(), "Writing triangles");
  }
}

void writeLayers(GDALDataset& ds, const Tin& tin, const GpkgWriteOptions& options,
                 const ProgressRange& progress) {
  deleteOurLayers(ds);
  OGRSpatialReference srs;
  OGRSpatialReference* srsPtr = nullptr;
  if (!tin.crsWkt.empty() && srs.importFromWkt(tin.crsWkt.c_str()) == OGRERR_NONE) srsPtr = &srs;
  OGRLayer* vertices = createLayer(ds, "vertices", wkbPoint25D, srsPtr, {"id", "row", "col", "outline"});
  OGRLayer* triangles = createLayer(ds, "triangles", wkbPolygon25D, srsPtr, {"id", "v0", "v1", "v2"});
  if (ds.StartTransaction() != OGRERR_NONE) throw Error("cannot start a GeoPackage transaction");
  const double share = double(tin.vertices.size()) / (tin.vertices.size() + 2.0 * tin.triangles.size());
  writeVertices(tin, *vertices, progress.sub(0, share));
  writeTriangles(tin, *triangles, progress.sub(share, 1));
  if (ds.CommitTransaction() != OGRERR_NONE) throw Error("cannot commit to the GeoPackage");
  for (const auto& [key, value] : options.metadata) ds.SetMetadataItem(key.c_str(), value.c_str());
}

}  // namespace

void checkOutputPath(const std::string& path, const GpkgWriteOptions& options) {
  const fs::path out(path);
  if (lower(out.extension().string()) != ".gpkg")
    throw Error("output '" + path + "' must be a GeoPackage file ending in .gpkg");
  const fs::path dir = out.parent_path().empty() ? fs::path(".") : out.parent_path();
  if (!fs::is_directory(dir)) throw Error("the folder of output '" + path + "' does not exist");
  if (access(dir.c_str(), W_OK) != 0) throw Error("the folder of output '" + path + "' is not writable");
  if (fs::is_directory(out)) throw Error("output '" + path + "' is a folder: name a .gpkg file");
  if (fs::exists(out) && !options.overwrite)
    throw Error("output '" + path +
                "' exists: add -overwrite to replace its tinlod layers (its other layers are kept)");
}

void writeTinGpkg(const Tin& tin, const std::string& path, const GpkgWriteOptions& options,
                  const ProgressRange& progress) {
  checkOutputPath(path, options);
  TemporaryOutput::removeStale(path);
  TemporaryOutput tmp{fs::path(path)};
  const bool fromCopy = fs::exists(tmp.output());
  if (fromCopy) {
    std::error_code ec;
    fs::copy_file(tmp.output(), tmp.path(), fs::copy_options::overwrite_existing, ec);
    if (ec) throw Error("cannot copy '" + path + "' to update it: " + ec.message());
  }
  GDALDataset* ds = openOrCreate(tmp.path(), fromCopy);
  if (!ds)
    throw Error(fromCopy ? "'" + path + "' exists but is not a GeoPackage GDAL can update: remove it or choose another name"
                         : "cannot create GeoPackage '" + path + "': " + CPLGetLastErrorMsg());
  try {
    // Features take the first 70 %; GDAL builds the spatial indexes while closing the
    // file, in SQLite statements that cannot be interrupted.
    writeLayers(*ds, tin, options, progress.sub(0, 0.7));
    progress.report(0.7, "Building the spatial index");
  } catch (...) {
    GDALClose(ds);
    throw;
  }
  // GDAL 3.6's GDALClose returns nothing: a failed final write shows as a CPL error.
  CPLErrorReset();
  GDALClose(ds);
  if (CPLGetLastErrorType() >= CE_Failure)
    throw Error("cannot finish GeoPackage '" + path + "': " + CPLGetLastErrorMsg());
  // Nothing is committed before the rename: a cancel asked for during the index build
  // is still honoured here.
  progress.report(0.99, "Building the spatial index");
  tmp.commit();
}

}  // namespace tinlod
