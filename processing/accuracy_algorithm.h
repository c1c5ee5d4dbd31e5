// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include "dem_algorithm.h"

namespace tinlod::qgis {

// tinlod:accuracy, "Accuracy of a TIN hierarchy": the Processing face of `tinlod accuracy`.
class AccuracyAlgorithm : public DemAlgorithm {
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
  AccuracyAlgorithm* createInstance() const override;
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
};

}  // namespace tinlod::qgis
