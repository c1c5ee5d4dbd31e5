// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <qgsprocessingalgorithm.h>

#include <string>

#include "tinlod/line_layers.h"

namespace tinlod::qgis {

// tinlod:concavity, "Polyline concavity": the Processing face of `tinlod lines concavity`.
class ConcavityAlgorithm : public QgsProcessingAlgorithm {
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
  ConcavityAlgorithm* createInstance() const override;
  void initAlgorithm(const QVariantMap& configuration = QVariantMap()) override;

 protected:
  bool prepareAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                        QgsProcessingFeedback* feedback) override;
  QVariantMap processAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                               QgsProcessingFeedback* feedback) override;

 private:
  std::string lines_;
  ConcavityOptions options_;
};

}  // namespace tinlod::qgis
