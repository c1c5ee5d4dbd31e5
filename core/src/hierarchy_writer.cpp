// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/hierarchy_writer.h"

#include "gpkg_output.h"
#include "tin_layers.h"

namespace tinlod {
namespace {

void setOptionalId(OGRFeature& f, const char* field, std::int32_t zeroBased) {
  if (zeroBased < 0) f.SetFieldNull(f.GetFieldIndex(field));
  else f.SetField(field, zeroBased + 1);
}

void writeGroups(const Hierarchy& h, OGRLayer& layer, const ProgressRange& progress) {
  OGRFeature feature(layer.GetLayerDefn());
  for (std::size_t g = 0; g < h.groups.size(); ++g) {
    const Group& group = h.groups[g];
    auto* ring = new OGRLinearRing();
    for (std::uint32_t k = group.ringBegin; k <= group.ringEnd; ++k) {
      const TinVertex& v = h.base.vertices[h.rings[k == group.ringEnd ? group.ringBegin : k]];
      ring->addPoint(v.x, v.y, v.z);
    }
    auto* polygon = new OGRPolygon();
    polygon->addRingDirectly(ring);
    feature.SetFID(static_cast<GIntBig>(g) + 1);
    feature.SetField("id", static_cast<int>(g) + 1);
    feature.SetField("level", group.level);
    feature.SetField("vertex", static_cast<int>(group.vertex) + 1);
    feature.SetField("importance", group.importance);
    feature.SetField("error", group.error);
    feature.SetGeometryDirectly(polygon);
    writeFeature(layer, feature);
    if ((g & 0x3FFF) == 0) progress.report(double(g) / h.groups.size(), "Writing groups");
  }
}

void writeLevels(const Hierarchy& h, OGRLayer& layer) {
  OGRFeature feature(layer.GetLayerDefn());
  for (const LevelStats& l : h.levels) {
    feature.SetFID(l.level + 1);
    feature.SetField("level", l.level);
    feature.SetField("vertices", static_cast<GIntBig>(l.vertices));
    feature.SetField("triangles", static_cast<GIntBig>(l.triangles));
    feature.SetField("deleted", static_cast<GIntBig>(l.deleted));
    feature.SetField("select_seconds", l.selectSeconds);
    feature.SetField("delete_seconds", l.deleteSeconds);
    feature.SetField("max_error", l.maxError);
    feature.SetField("rmse", l.rmse);
    feature.SetField("cells", static_cast<GIntBig>(l.cells));
    feature.SetField("cells_given_up", static_cast<GIntBig>(h.levels.front().cells - l.cells));
    feature.SetField("outline_vertices", static_cast<GIntBig>(l.outlineVertices));
    feature.SetField("method", measureName(h.options.measure).c_str());
    feature.SetField("delete_pct", h.options.deletePct);
    feature.SetField("stop_pct", h.options.stopPct);
    writeFeature(layer, feature);
  }
}

void createLevelViews(const Hierarchy& h, GpkgOutput& out) {
  out.executeAfterClose("CREATE INDEX triangles_levels ON triangles (first_level, last_level)");
  out.executeAfterClose("CREATE INDEX triangles_group ON triangles (group_id)");
  out.executeAfterClose("CREATE INDEX triangles_replaced_by ON triangles (replaced_by)");
  for (std::int32_t L = 0; L <= h.coarsest(); ++L) {
    const std::string level = std::to_string(L);
    out.createFeatureView("level_" + level,
                          "SELECT fid, id, v0, v1, v2, error, geom FROM triangles WHERE first_level <= " + level +
                              " AND last_level >= " + level,
                          "triangles", "TIN level " + level);
  }
}

}  // namespace

void writeHierarchyGpkg(const Hierarchy& h, const std::string& path, const GpkgWriteOptions& options,
                        const ProgressRange& progress) {
  checkOutputPath(path, options);
  OutputFiles files(options.overwrite);
  writeHierarchyGpkg(h, files.add(path, "output", true), options, progress);
  files.commit();
}

void writeHierarchyGpkg(const Hierarchy& h, const StagedFile& file, const GpkgWriteOptions& options,
                        const ProgressRange& progress) {
  GpkgOutput out(file, options, isTinlodLayer);
  const std::string& crs = h.base.crsWkt;
  std::vector<FieldSpec> vfields = vertexFields();
  vfields.push_back({"level"});
  vfields.push_back({"fixed", OFTInteger, OFSTBoolean});
  std::vector<FieldSpec> tfields = triangleFields();
  for (const char* f : {"first_level", "last_level", "group_id", "replaced_by"}) tfields.push_back({f});
  tfields.push_back({"error", OFTReal});
  OGRLayer* vertices = out.createLayer("vertices", wkbPoint25D, crs, vfields);
  OGRLayer* triangles = out.createLayer("triangles", wkbPolygon25D, crs, tfields);
  OGRLayer* groups = out.createLayer("groups", wkbPolygon25D, crs,
                                     {{"id"}, {"level"}, {"vertex"}, {"importance", OFTReal}, {"error", OFTReal}});
  OGRLayer* levels = out.createLayer("levels", wkbNone, "",
                                     {{"level"}, {"vertices", OFTInteger64}, {"triangles", OFTInteger64},
                                      {"deleted", OFTInteger64}, {"select_seconds", OFTReal},
                                      {"delete_seconds", OFTReal}, {"max_error", OFTReal}, {"rmse", OFTReal},
                                      {"cells", OFTInteger64}, {"cells_given_up", OFTInteger64},
                                      {"outline_vertices", OFTInteger64}, {"method", OFTString},
                                      {"delete_pct", OFTReal}, {"stop_pct", OFTReal}});
  std::vector<Triangle> corners;
  corners.reserve(h.triangles.size());
  for (const HierarchyTriangle& t : h.triangles) corners.push_back(t.v);

  out.begin();
  const double n = h.base.vertices.size() + 2.0 * h.triangles.size() + 2.0 * h.groups.size();
  const double v1 = 0.7 * h.base.vertices.size() / n, t1 = v1 + 0.7 * 2.0 * h.triangles.size() / n;
  writeVertices(h.base, *vertices, [&](OGRFeature& f, std::size_t i) {
    f.SetField("level", h.vertexLevel[i]);
    f.SetField("fixed", h.fixed[i] ? 1 : 0);
  }, progress.sub(0, v1));
  writeTriangles(h.base, corners, *triangles, [&](OGRFeature& f, std::size_t i) {
    const HierarchyTriangle& t = h.triangles[i];
    f.SetField("first_level", t.firstLevel);
    f.SetField("last_level", t.lastLevel);
    setOptionalId(f, "group_id", t.group);
    setOptionalId(f, "replaced_by", t.replacedBy);
    f.SetField("error", t.error);
  }, progress.sub(v1, t1));
  writeGroups(h, *groups, progress.sub(t1, 0.7));
  writeLevels(h, *levels);
  createLevelViews(h, out);
  out.commit();
  out.finish(progress);
}

}  // namespace tinlod
