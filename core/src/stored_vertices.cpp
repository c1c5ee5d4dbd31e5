// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>
#include <vector>

#include "stored_hierarchy.h"
#include "text_and_paths.h"

namespace tinlod {
namespace {

// No CRS has coordinates this far out; bounding them keeps every later sum, square and
// conversion to a grid cell finite.
constexpr double kMaxCoordinate = 1e12;
constexpr std::int64_t kMaxVertices = UINT32_MAX - 1;  // VertexId, with UINT32_MAX kept for "none"

// Field positions looked up once: by name, each row would search them again.
struct VertexColumns {
  int id, row, col, outline, level = -1, fixed = -1;
};

VertexColumns vertexColumns(const StoredTable& table, bool levelled) {
  VertexColumns c{table.column("id"), table.column("row"), table.column("col"), table.column("outline")};
  if (levelled) c.level = table.column("level"), c.fixed = table.column("fixed");
  return c;
}

TinVertex vertexOf(const StoredRow& row, const OGRFeature& f, const VertexColumns& c) {
  const auto* p = dynamic_cast<const OGRPoint*>(f.GetGeometryRef());
  if (!p || p->IsEmpty()) row.damaged("has no point");
  TinVertex v;
  v.x = p->getX(), v.y = p->getY(), v.z = p->getZ();
  if (!(std::fabs(v.x) <= kMaxCoordinate && std::fabs(v.y) <= kMaxCoordinate && std::isfinite(v.z)))
    row.damaged("has a point at (" + formatNumber(v.x) + ", " + formatNumber(v.y) + ", " + formatNumber(v.z) +
                "): coordinates must be finite, x and y within 1e12");
  v.row = f.GetFieldAsInteger(c.row), v.col = f.GetFieldAsInteger(c.col);
  v.outline = f.GetFieldAsInteger(c.outline) != 0;
  return v;
}

}  // namespace

void readStoredVertices(const StoredTable& table, Hierarchy& h, bool levelled, std::uintmax_t fileBytes,
                        const ProgressRange& progress) {
  const VertexColumns c = vertexColumns(table, levelled);
  const std::size_t expected = table.plausibleRows(fileBytes);
  std::vector<std::int64_t> ids;
  std::vector<GIntBig> fids;
  ids.reserve(expected), fids.reserve(expected), h.base.vertices.reserve(expected);
  for (auto& f : table.layer()) {
    const StoredRow row(table, *f);
    ids.push_back(row.integer(c.id, 1, kMaxVertices, "vertex ids"));
    fids.push_back(f->GetFID());
    h.base.vertices.push_back(vertexOf(row, *f, c));
    h.vertexLevel.push_back(levelled ? static_cast<std::int32_t>(row.integer(c.level, 0, h.coarsest(), "levels")) : 0);
    h.fixed.push_back(levelled && f->GetFieldAsInteger(c.fixed) != 0);
    if ((ids.size() & 0xFFFF) == 0)
      progress.report(double(ids.size()) / std::max<std::size_t>(1, expected), "Reading vertices");
  }
  table.checkFullyRead();
  const std::vector<std::size_t> rows = table.rowsById(ids, fids);
  orderById(h.base.vertices, rows), orderById(h.vertexLevel, rows), orderById(h.fixed, rows);
}

}  // namespace tinlod
