// SPDX-License-Identifier: GPL-3.0-or-later
#include "provider.h"


#include "accuracy_algorithm.h"
#include "build_hierarchy_algorithm.h"
#include "concavity_algorithm.h"
#include "dp_values_algorithm.h"
#include "extract_lod_algorithm.h"
#include "group_icon.h"
#include "greedy_insertion_algorithm.h"
#include "locate_algorithm.h"
#include "sample_tin_algorithm.h"
#include "tinlod/version.h"

namespace tinlod::qgis {

QString Provider::id() const { return QStringLiteral("tinlod"); }
QString Provider::name() const { return QStringLiteral("TIN hierarchy"); }
QString Provider::longName() const { return QStringLiteral("TIN hierarchy (tinlod %1)").arg(kVersion); }
QString Provider::versionInfo() const { return QString::fromLatin1(kVersion); }
QIcon Provider::icon() const { return providerIcon(); }

void Provider::loadAlgorithms() {
  addAlgorithm(new AccuracyAlgorithm());
  addAlgorithm(new BuildHierarchyAlgorithm());
  addAlgorithm(new ConcavityAlgorithm());
  addAlgorithm(new DpValuesAlgorithm());
  addAlgorithm(new ExtractLodAlgorithm());
  addAlgorithm(new GreedyInsertionAlgorithm());
  addAlgorithm(new LocateAlgorithm());
  addAlgorithm(new SampleTinAlgorithm());
}

}  // namespace tinlod::qgis
