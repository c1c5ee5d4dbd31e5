// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/hierarchy_reader.h"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "gdal_handles.h"
#include "tinlod/error.h"

namespace tinlod {
namespace {

std::string wktOf(OGRLayer& layer) {
  const OGRSpatialReference* srs = layer.GetSpatialRef();
  return srs ? wkt2(*srs) : "";
}

void readVertices(OGRLayer& layer, Hierarchy& h, const ProgressRange& progress) {
  const GIntBig count = layer.GetFeatureCount();
  h.base.vertices.assign(static_cast<std::size_t>(count), TinVertex());
  h.vertexLevel.assign(static_cast<std::size_t>(count), 0);
  h.fixed.assign(static_cast<std::size_t>(count), 0);
  // Field positions looked up once: by name, each feature would search them again.
  OGRFeatureDefn& defn = *layer.GetLayerDefn();
  const int idField = defn.GetFieldIndex("id"), rowField = defn.GetFieldIndex("row"), colField = defn.GetFieldIndex("col");
  const int outline = defn.GetFieldIndex("outline"), level = defn.GetFieldIndex("level"), fixed = defn.GetFieldIndex("fixed");
  std::size_t seen = 0;
  for (auto& f : layer) {
    const GIntBig id = f->GetFieldAsInteger64(idField) - 1;
    const auto* p = dynamic_cast<const OGRPoint*>(f->GetGeometryRef());
    if (id < 0 || id >= count || !p) throw Error("the vertices layer of the GeoPackage is damaged (vertex ids out of range)");
    TinVertex& v = h.base.vertices[static_cast<std::size_t>(id)];
    v.x = p->getX(), v.y = p->getY(), v.z = p->getZ();
    v.row = f->GetFieldAsInteger(rowField), v.col = f->GetFieldAsInteger(colField);
    v.outline = f->GetFieldAsInteger(outline) != 0;
    if (level >= 0) h.vertexLevel[static_cast<std::size_t>(id)] = f->GetFieldAsInteger(level);
    if (fixed >= 0) h.fixed[static_cast<std::size_t>(id)] = f->GetFieldAsInteger(fixed) != 0;
    if ((++seen & 0xFFFF) == 0) progress.report(double(seen) / count, "Reading vertices");
  }
}

// `levelled`: the file is a hierarchy; any other (a TIN, a level-of-detail TIN, whose
// triangles keep their levels as plain attributes) is one level of its own.
void readTriangles(OGRLayer& layer, Hierarchy& h, bool levelled, const ProgressRange& progress) {
  const GIntBig count = layer.GetFeatureCount();
  const std::size_t vertices = h.base.vertices.size();
  OGRFeatureDefn& defn = *layer.GetLayerDefn();
  const int first = defn.GetFieldIndex("first_level"), last = defn.GetFieldIndex("last_level");
  const int corner[3] = {defn.GetFieldIndex("v0"), defn.GetFieldIndex("v1"), defn.GetFieldIndex("v2")};
  const int group = defn.GetFieldIndex("group_id"), replacedBy = defn.GetFieldIndex("replaced_by");
  const int error = defn.GetFieldIndex("error");
  // Null (level 0, or never replaced) and absent (a plain TIN) both read as no group.
  auto groupOf = [&](OGRFeature& f, int field) {
    return field >= 0 && f.IsFieldSetAndNotNull(field) ? f.GetFieldAsInteger(field) - 1 : kNoGroup;
  };
  layer.SetIgnoredFields(std::vector<const char*>{"OGR_GEOMETRY", nullptr}.data());  // corners come from v0..v2
  h.triangles.reserve(static_cast<std::size_t>(count));
  for (auto& f : layer) {
    HierarchyTriangle t;
    for (int k = 0; k < 3; ++k) {
      const GIntBig v = f->GetFieldAsInteger64(corner[k]) - 1;
      if (v < 0 || static_cast<std::size_t>(v) >= vertices)
        throw Error("the triangles layer of the GeoPackage is damaged (a corner is not a vertex)");
      t.v[k] = static_cast<VertexId>(v);
    }
    t.firstLevel = levelled && first >= 0 ? f->GetFieldAsInteger(first) : 0;
    t.lastLevel = levelled && last >= 0 ? f->GetFieldAsInteger(last) : 0;
    t.group = levelled ? groupOf(*f, group) : kNoGroup;
    t.replacedBy = levelled ? groupOf(*f, replacedBy) : kNoGroup;
    if (error >= 0) t.error = f->GetFieldAsDouble(error);
    if (t.firstLevel == 0) h.base.triangles.push_back(t.v);
    h.triangles.push_back(t);
    if ((h.triangles.size() & 0xFFFF) == 0) progress.report(double(h.triangles.size()) / count, "Reading triangles");
  }
}

// The groups' accept and reject triangles come from the triangles' replaced_by and
// group_id: each group's range in h.links holds its accept triangles, then its reject ones.
void linkGroups(Hierarchy& h) {
  std::vector<std::uint32_t> accepts(h.groups.size(), 0), rejects(h.groups.size(), 0);
  auto check = [&](std::int32_t g) {
    if (g != kNoGroup && (g < 0 || static_cast<std::size_t>(g) >= h.groups.size()))
      throw Error("the triangles layer of the GeoPackage is damaged (a group id is not a group)");
    return g != kNoGroup;
  };
  for (const HierarchyTriangle& t : h.triangles) {
    if (check(t.replacedBy)) ++accepts[t.replacedBy];
    if (check(t.group)) ++rejects[t.group];
  }
  std::uint32_t next = 0;
  for (std::size_t g = 0; g < h.groups.size(); ++g) {
    if (accepts[g] == 0 || rejects[g] == 0)
      throw Error("the GeoPackage's group " + std::to_string(g + 1) + " has no accept or no reject triangle: the file is damaged");
    Group& group = h.groups[g];
    group.acceptBegin = group.acceptEnd = next;
    group.rejectBegin = group.rejectEnd = next += accepts[g];
    next += rejects[g];
  }
  h.links.assign(next, 0);
  for (std::uint32_t t = 0; t < h.triangles.size(); ++t) {
    if (h.triangles[t].replacedBy != kNoGroup) h.links[h.groups[h.triangles[t].replacedBy].acceptEnd++] = t;
    if (h.triangles[t].group != kNoGroup) h.links[h.groups[h.triangles[t].group].rejectEnd++] = t;
  }
}

void readGroups(OGRLayer& layer, Hierarchy& h) {
  const GIntBig count = layer.GetFeatureCount();
  h.groups.assign(static_cast<std::size_t>(count), Group());
  OGRFeatureDefn& defn = *layer.GetLayerDefn();
  const int id = defn.GetFieldIndex("id"), level = defn.GetFieldIndex("level"), vertex = defn.GetFieldIndex("vertex");
  const int importance = defn.GetFieldIndex("importance"), error = defn.GetFieldIndex("error");
  layer.SetIgnoredFields(std::vector<const char*>{"OGR_GEOMETRY", nullptr}.data());  // the outlines are not read
  for (auto& f : layer) {
    const GIntBig g = f->GetFieldAsInteger64(id) - 1;
    const GIntBig v = f->GetFieldAsInteger64(vertex) - 1;
    if (g < 0 || g >= count || v < 0 || static_cast<std::size_t>(v) >= h.base.vertices.size())
      throw Error("the groups layer of the GeoPackage is damaged (ids out of range)");
    Group& group = h.groups[static_cast<std::size_t>(g)];
    group.vertex = static_cast<VertexId>(v);
    group.level = f->GetFieldAsInteger(level);
    group.importance = f->GetFieldAsDouble(importance);
    group.error = f->GetFieldAsDouble(error);
  }
  linkGroups(h);
}

void readOptions(const HierarchyInfo& info, Hierarchy& h) {
  h.levels = info.levels;
  auto item = [&](const char* key) { auto it = info.metadata.find(key); return it == info.metadata.end() ? std::string() : it->second; };
  if (info.kind != "hierarchy") {
    h.tinMethod = item("method").empty() ? "sample" : item("method");
    return;
  }
  if (!item("method").empty()) h.options.measure = parseMeasure(item("method"));
  h.options.deletePct = std::atof(item("delete_pct").c_str());
  h.options.stopPct = std::atof(item("stop_pct").c_str());
}

}  // namespace

StoredHierarchy readHierarchy(const std::string& path, const ProgressRange& progress) {
  StoredHierarchy out;
  out.info = readHierarchyInfo(path);  // also refuses files tinlod did not write
  const char* const gpkgOnly[] = {"GPKG", nullptr};
  const DatasetPtr ds = openReadOnly(path, GDAL_OF_VECTOR, gpkgOnly);
  OGRLayer* vertices = ds ? ds->GetLayerByName("vertices") : nullptr;
  OGRLayer* triangles = ds ? ds->GetLayerByName("triangles") : nullptr;
  if (!vertices || !triangles) throw Error("'" + path + "' has no vertices or triangles layer: it is not a tinlod TIN");
  Hierarchy& h = out.hierarchy;
  h.base.crsWkt = wktOf(*triangles);
  h.base.crsName = out.info.crsName;
  readVertices(*vertices, h, progress.sub(0, 0.2));
  const bool levelled = out.info.kind == "hierarchy";
  readTriangles(*triangles, h, levelled, progress.sub(0.2, 0.95));
  if (levelled) {
    OGRLayer* groups = ds->GetLayerByName("groups");
    if (!groups) throw Error("'" + path + "' has no groups layer: the hierarchy is damaged; build it again with tinlod build");
    readGroups(*groups, h);
  }
  readOptions(out.info, h);
  return out;
}

}  // namespace tinlod
