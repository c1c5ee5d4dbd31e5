// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include "dem_algorithm.h"
#include "tinlod/hierarchy_layers.h"
#include "tinlod/hierarchy_options.h"

namespace tinlod::qgis {

// tinlod:buildhierarchy, "Build TIN hierarchy from DEM": the Processing face of `tinlod build`.
class BuildHierarchyAlgorithm : public DemAlgorithm {
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
  BuildHierarchyAlgorithm* createInstance() const override;
  void initAlgorithm(const QVariantMap& configuration = QVariantMap()) override;

 protected:
  bool prepareAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                        QgsProcessingFeedback* feedback) override;
  QVariantMap processAlgorithm(const QVariantMap& parameters, QgsProcessingContext& context,
                               QgsProcessingFeedback* feedback) override;

 private:
  // The core's options by the dialog's parameters, for its messages.
  static ParameterNames parameterNames();
  HierarchyOptions options_;
  HierarchyLayers layers_;
  bool loadLevels_ = true;
};

}  // namespace tinlod::qgis
