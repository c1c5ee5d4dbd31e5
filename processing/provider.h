// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <qgsprocessingprovider.h>

namespace tinlod::qgis {

// The "TIN hierarchy" provider (id "tinlod") in the Processing toolbox and qgis_process.
class Provider : public QgsProcessingProvider {
 public:
  QString id() const override;
  QString name() const override;
  QString longName() const override;
  QString versionInfo() const override;
  QIcon icon() const override;

 protected:
  void loadAlgorithms() override;
};

}  // namespace tinlod::qgis
