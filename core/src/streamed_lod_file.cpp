// SPDX-License-Identifier: GPL-3.0-or-later
#include "streamed_lod_file.h"

#include <map>
#include <string>
#include <utility>

#include "tin_layers.h"

namespace tinlod {
namespace {

// The extra fields of tinlod lod's layers, as ExtraField (the names and kinds make the layers).
std::vector<ExtraField> vertexExtra(std::vector<double> level = {}) { return {{"level", std::move(level), true}}; }
std::vector<ExtraField> triangleExtra(std::vector<double> first = {}, std::vector<double> last = {}) {
  return {{"first_level", std::move(first), true}, {"last_level", std::move(last), true}};
}

}  // namespace

StreamedLodFile::StreamedLodFile(const StagedFile& file, GpkgWriteOptions options)
    : stagedFile_(file), options_(std::move(options)) {}

void StreamedLodFile::start(const std::string& crsWkt, const std::string& crsName) {
  crsName_ = crsName;
  options_.metadata["TINLOD_CRS"] = crsName;
  // Known only after the last tile: written with the indexes, as a single TIN's file has it.
  options_.lateMetadata = [this] { return std::map<std::string, std::string>{{"TINLOD_OUTLINE_VERTICES", std::to_string(outlineVertices_)}}; };
  file_ = std::make_unique<TinGpkgFile>(stagedFile_, options_, crsWkt, vertexExtra(), triangleExtra());
}

void StreamedLodFile::add(const LodPiece& piece, const ProgressRange& progress) {
  const ExtractedLod& part = piece.part;
  std::vector<TinVertex> fresh;
  std::vector<double> levels;
  for (std::size_t v = 0; v < part.tin.vertices.size(); ++v) {
    if (!piece.isNew[v]) continue;
    const TinVertex& p = part.tin.vertices[v];
    fresh.push_back(p), levels.push_back(part.vertexLevel[v]);
    extent_.extend(p.x, p.y);
    if (file_->vertexIndex()) vertexBoxes_.push_back(outwardBox({p.x, p.x, p.y, p.y}));
  }
  const std::vector<ExtraField> vExtra = vertexExtra(std::move(levels));
  const std::vector<ExtraField> tExtra = triangleExtra(part.firstLevel, part.lastLevel);
  const double share = double(fresh.size()) / (fresh.size() + 2.0 * part.tin.triangles.size());
  writeVertexRows(fresh, std::int64_t(vertices_) + 1, file_->vertexRows(), file_->srsId(),
                  extraSetter(vExtra, int(vertexFields().size())), progress.sub(0, share));
  const TriangleAt triangle = [&part](std::size_t i) -> const Triangle& { return part.tin.triangles[i]; };
  writeTriangleRows(part.tin.vertices, part.tin.triangles.size(), triangle, piece.id, std::int64_t(triangles_) + 1,
                    file_->triangleRows(), file_->srsId(), extraSetter(tExtra, int(triangleFields().size())),
                    progress.sub(share, 1));
  addTriangleBoxes(part.tin.vertices, part.tin.triangles.size(), triangle, triangleBoxes_);
  for (double level : part.firstLevel) {
    const std::size_t L = static_cast<std::size_t>(level);
    if (L >= byFirstLevel_.size()) byFirstLevel_.resize(L + 1, 0);
    ++byFirstLevel_[L];
  }
  vertices_ += fresh.size();
  triangles_ += part.tin.triangles.size();
}

void StreamedLodFile::setOutline(const std::vector<VertexId>& sharedOutline, std::size_t outlineVertices) {
  outlineVertices_ = outlineVertices;
  file_->vertexRows().flush();  // the last tile's vertices may be waiting in the batch
  SqliteStatement update = file_->database().prepare("UPDATE vertices SET outline = 1 WHERE fid = ?");
  for (VertexId v : sharedOutline) {
    update.bind(1, std::int64_t(v) + 1);
    update.step();
    update.reset();
  }
}

void StreamedLodFile::finish(const ProgressRange& progress) {
  file_->finishRows(std::move(vertexBoxes_), std::move(triangleBoxes_), progress);
}

}  // namespace tinlod
