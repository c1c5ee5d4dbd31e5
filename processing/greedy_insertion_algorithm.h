// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include "dem_algorithm.h"
#include "tinlod/insert_options.h"

namespace tinlod::qgis {

// tinlod:greedyinsertion, "Greedy insertion TIN": the Processing face of `tinlod insert`.
class GreedyInsertionAlgorithm : public DemAlgorithm {
 public:
  QString name() const override;
  QString displayName() const override;
  QString group() const override;
  QString groupId() const override;
  QStringList tags() const override;
  QString shortHelpString() const override;
  QString shortDescription() const override;
  QIcon icon() const override;
  QString helpUrl() const override;
  GreedyInsertionAlgorithm* createInstance() const override;
  void initAlgorithm(const QVariantMap& configuration = QVariantMap()) override;

 protected:
  bool prepareAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                        QgsProcessingFeedback* feedback) override;
  QVariantMap processAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                               QgsProcessingFeedback* feedback) override;

 private:
  InsertOptions insert_;
};

}  // namespace tinlod::qgis
