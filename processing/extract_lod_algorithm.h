// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <qgsprocessingalgorithm.h>

#include "tinlod/lod_job.h"

namespace tinlod::qgis {

// tinlod:extractlod, "Extract variable level-of-detail TIN": the Processing face of `tinlod lod`.
class ExtractLodAlgorithm : public QgsProcessingAlgorithm {
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
  ExtractLodAlgorithm* createInstance() const override;
  void initAlgorithm(const QVariantMap& configuration = QVariantMap()) override;
  bool checkParameterValues(const QVariantMap& parameters, QgsProcessingContext& context,
                            QString* message = nullptr) const override;

 protected:
  bool prepareAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                        QgsProcessingFeedback* feedback) override;
  QVariantMap processAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                               QgsProcessingFeedback* feedback) override;

 private:
  std::string hierarchy_;
  LodJobOptions options_;
};

}  // namespace tinlod::qgis
