// SPDX-License-Identifier: GPL-3.0-or-later
#include "surface_comparison.h"

#include <algorithm>
#include <mutex>
#include <utility>

#include "parallel_blocks.h"

namespace tinlod {
namespace {

// The compared variables, in report order; aspect is an angle and compared as one.
const char* const kVariables[] = {"elevation", "slope", "aspect", "mean_curvature", "gaussian_curvature",
                                  "profile_curvature", "plan_curvature"};
constexpr int kAspect = 2;

std::array<double, SurfaceComparison::kVariableCount> variables(const TerrainMeasures& m) {
  return {m.z, m.slope, m.aspect, m.meanCurvature, m.gaussianCurvature, m.profileCurvature, m.planCurvature};
}

template <class S>
VariableComparison describeOne(const char* name, const S& s) {
  return {name, s.count(), s.correlation(), s.meanA(), s.meanB(), s.stdA(), s.stdB()};
}

}  // namespace

void SurfaceComparison::add(const TerrainMeasures& reference, const TerrainMeasures& simplified) {
  const auto a = variables(reference), b = variables(simplified);
  for (int k = 0; k < kVariableCount; ++k)
    if (k != kAspect) linear_[k].add(a[k], b[k]);
  aspect_.add(a[kAspect], b[kAspect]);
}

void SurfaceComparison::merge(const SurfaceComparison& other) {
  for (int k = 0; k < kVariableCount; ++k) linear_[k].merge(other.linear_[k]);
  aspect_.merge(other.aspect_);
}

std::vector<VariableComparison> SurfaceComparison::describe() const {
  std::vector<VariableComparison> out;
  for (int k = 0; k < kVariableCount; ++k)
    out.push_back(k == kAspect ? describeOne(kVariables[k], aspect_) : describeOne(kVariables[k], linear_[k]));
  return out;
}

SurfaceComparison compareSurfaces(const BsplineSurface& reference, const BsplineSurface& simplified, const TestRect& rect,
                                  AccuracyBands* bands, int bandsRow0, const ProgressRange& progress) {
  std::vector<std::pair<int, SurfaceComparison>> blocks;
  std::mutex mutex;
  auto work = [&](int begin, int end) {
    SurfaceComparison local;
    std::vector<SurfacePoint> refRow, simpRow;
    for (int r = rect.row0 + begin; r < rect.row0 + end; ++r) {
      reference.evaluateRow(r, refRow);
      simplified.evaluateRow(r, simpRow);
      for (int c = rect.col0; c < rect.col1; ++c) {
        const TerrainMeasures a = terrainMeasures(refRow[c]), b = terrainMeasures(simpRow[c]);
        local.add(a, b);
        if (bands) {
          bands->meanCurvatureReference.at(c, r - bandsRow0) = a.meanCurvature;
          bands->meanCurvatureSimplified.at(c, r - bandsRow0) = b.meanCurvature;
          bands->meanCurvatureDifference.at(c, r - bandsRow0) = b.meanCurvature - a.meanCurvature;
        }
      }
    }
    std::lock_guard<std::mutex> lock(mutex);
    blocks.emplace_back(begin, local);
  };
  if (!rect.empty())
    forEachBlock(rect.row1 - rect.row0, work, [&](double f) { progress.report(f, "Comparing curvature"); });
  std::sort(blocks.begin(), blocks.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  SurfaceComparison total;
  for (const auto& block : blocks) total.merge(block.second);
  return total;
}

}  // namespace tinlod
