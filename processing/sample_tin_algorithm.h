// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include "dem_algorithm.h"

namespace tinlod::qgis {

// tinlod:sampletin, "Sample TIN from DEM": the Processing face of `tinlod sample`.
class SampleTinAlgorithm : public DemAlgorithm {
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
  SampleTinAlgorithm* createInstance() const override;
  void initAlgorithm(const QVariantMap& configuration = QVariantMap()) override;

 protected:
  bool prepareAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                        QgsProcessingFeedback* feedback) override;
  QVariantMap processAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                               QgsProcessingFeedback* feedback) override;
};

}  // namespace tinlod::qgis
