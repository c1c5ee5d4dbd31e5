// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/hierarchy_writer.h"

#include <algorithm>

#include "gpkg_output.h"
#include "tin_layers.h"

namespace tinlod {
namespace {

void setOptionalId(GpkgFeatureRows& rows, int field, std::int32_t zeroBased) {
  if (zeroBased < 0) rows.setNull(field);
  else rows.set(field, zeroBased + 1);
}

// The outline's corners, the ring closed by the writer.
template <class Visit>
void ringOf(const Hierarchy& h, const Group& group, Visit visit) {
  for (std::uint32_t k = group.ringBegin; k < group.ringEnd; ++k) visit(h.base.vertices[h.rings[k]]);
}

void writeGroups(const Hierarchy& h, GpkgFeatureRows& rows, std::int32_t srsId, bool outlines,
                 const ProgressRange& progress) {
  GpkgGeometryBlob polygon(srsId);
  for (std::size_t g = 0; g < h.groups.size(); ++g) {
    const Group& group = h.groups[g];
    rows.set(0, static_cast<std::int64_t>(g) + 1);
    rows.set(1, group.level);
    rows.set(2, static_cast<std::int64_t>(group.vertex) + 1);
    rows.setReal(3, group.importance);
    rows.setReal(4, group.error);
    if ((g & 0x3FFF) == 0) progress.report(double(g) / h.groups.size(), "Writing groups");
    if (!outlines) {
      rows.insert(static_cast<std::int64_t>(g) + 1);
      continue;
    }
    // 2D: the heights of an outline are its vertices', already in the vertices layer, and
    // would cost 8 bytes a corner (9 bytes a stored triangle).
    polygon.polygon(group.ringEnd - group.ringBegin, [&](std::size_t k, double& x, double& y, double& z) {
      const TinVertex& v = h.base.vertices[h.rings[group.ringBegin + k]];
      x = v.x, y = v.y, z = 0;
    }, false);
    rows.insert(static_cast<std::int64_t>(g) + 1, polygon);
  }
  rows.finish();
}

std::vector<RtreeBox> groupBoxes(const Hierarchy& h) {
  std::vector<RtreeBox> boxes;
  boxes.reserve(h.groups.size());
  for (const Group& group : h.groups) {
    Envelope e = Envelope::empty();
    ringOf(h, group, [&](const TinVertex& v) { e.extend(v.x, v.y); });
    boxes.push_back(outwardBox(e));
  }
  return boxes;
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

// Each level's view reads a range of fids: the triangles are stored finest level first,
// so those of level L or finer end at fid lastFid[L], and SQLite reads no further. The
// level tests stay in the view, so it is right whatever the order; no index is needed.
void createLevelViews(const Hierarchy& h, const HierarchyLayers& layers, GpkgOutput& out) {
  std::vector<std::size_t> lastFid(h.coarsest() + 1, 0);
  for (std::size_t i = 0; i < h.triangles.size(); ++i) {
    std::size_t& last = lastFid[h.triangles[i].firstLevel];
    last = std::max(last, i + 1);
  }
  for (std::size_t L = 1; L < lastFid.size(); ++L) lastFid[L] = std::max(lastFid[L], lastFid[L - 1]);
  for (std::int32_t L : layers.views(h.coarsest())) {
    const std::string level = std::to_string(L);
    out.createFeatureView("level_" + level,
                          "SELECT fid, id, v0, v1, v2, error, geom FROM triangles WHERE fid <= " +
                              std::to_string(lastFid[L]) + " AND first_level <= " + level + " AND last_level >= " + level,
                          "triangles", "TIN level " + level);
  }
}

}  // namespace

void writeHierarchyGpkg(const Hierarchy& h, const std::string& path, const GpkgWriteOptions& options,
                        const ProgressRange& progress, const HierarchyLayers& layers) {
  checkOutputPath(path, options);
  OutputFiles files(options.overwrite);
  writeHierarchyGpkg(h, files.add(path, "output", true), options, progress, layers);
  files.commit();
}

void writeHierarchyGpkg(const Hierarchy& h, const StagedFile& file, const GpkgWriteOptions& options,
                        const ProgressRange& progress, const HierarchyLayers& layers) {
  if (const std::vector<std::int32_t> missing = layers.missingLevels(h.coarsest()); !missing.empty())
    progress.warn("no view for level " + levelListText(missing) + ": the hierarchy has levels 0 to " +
                  std::to_string(h.coarsest()));
  GpkgOutput out(file, options, isTinlodLayer);
  const std::string& crs = h.base.crsWkt;
  std::vector<FieldSpec> vfields = vertexFields();
  vfields.push_back({"level"});
  vfields.push_back({"fixed", OFTInteger, OFSTBoolean});
  std::vector<FieldSpec> tfields = triangleFields();
  for (const char* f : {"first_level", "last_level", "group_id", "replaced_by"}) tfields.push_back({f});
  tfields.push_back({"error", OFTReal});
  const std::vector<FieldSpec> gfields{{"id"}, {"level"}, {"vertex"}, {"importance", OFTReal}, {"error", OFTReal}};
  out.createLayer("vertices", wkbPoint25D, crs, vfields, true);
  out.createLayer("triangles", wkbPolygon25D, crs, tfields, true);
  out.createLayer("groups", layers.groupOutlines ? wkbPolygon : wkbNone, crs, gfields, true);
  OGRLayer* levels = out.createLayer("levels", wkbNone, "",
                                     {{"level"}, {"vertices", OFTInteger64}, {"triangles", OFTInteger64},
                                      {"deleted", OFTInteger64}, {"select_seconds", OFTReal},
                                      {"delete_seconds", OFTReal}, {"max_error", OFTReal}, {"rmse", OFTReal},
                                      {"cells", OFTInteger64}, {"cells_given_up", OFTInteger64},
                                      {"outline_vertices", OFTInteger64}, {"method", OFTString},
                                      {"delete_pct", OFTReal}, {"stop_pct", OFTReal}});
  writeLevels(h, *levels);

  SqliteDatabase& db = out.database();
  if (layers.vertexIndex) out.indexLater("vertices", [&h] { return vertexBoxes(h.base); });
  const TriangleAt triangle = [&h](std::size_t i) -> const Triangle& { return h.triangles[i].v; };
  out.indexLater("triangles", [&h, triangle] { return triangleBoxes(h.base, h.triangles.size(), triangle); });
  if (layers.groupOutlines) out.indexLater("groups", [&h] { return groupBoxes(h); });

  const double rows = 0.75;
  const double n = h.base.vertices.size() + 2.0 * h.triangles.size() + 2.0 * h.groups.size();
  const double v1 = rows * h.base.vertices.size() / n, t1 = v1 + rows * 2.0 * h.triangles.size() / n;
  GpkgFeatureRows vertexRows(db, "vertices", fieldNames(vfields));
  writeVertices(h.base, vertexRows, out.srsId("vertices"), [&](GpkgFeatureRows& r, std::size_t i) {
    r.set(4, h.vertexLevel[i]);
    r.set(5, h.fixed[i] ? 1 : 0);
  }, progress.sub(0, v1));
  GpkgFeatureRows triangleRows(db, "triangles", fieldNames(tfields));
  writeTriangles(h.base, h.triangles.size(), triangle, triangleRows, out.srsId("triangles"), [&](GpkgFeatureRows& r, std::size_t i) {
    const HierarchyTriangle& t = h.triangles[i];
    r.set(4, t.firstLevel);
    r.set(5, t.lastLevel);
    setOptionalId(r, 6, t.group);
    setOptionalId(r, 7, t.replacedBy);
    r.setReal(8, t.error);
  }, progress.sub(v1, t1));
  GpkgFeatureRows groupRows(db, "groups", fieldNames(gfields), layers.groupOutlines);
  writeGroups(h, groupRows, layers.groupOutlines ? out.srsId("groups") : 0, layers.groupOutlines, progress.sub(t1, rows));
  createLevelViews(h, layers, out);
  out.finish(progress.sub(rows, 1));
}

}  // namespace tinlod
