// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <qgsprocessingparameters.h>

namespace tinlod::qgis {

// Shows a decimal parameter with `places` decimals in the dialog: a percentage as 20.0,
// not QGIS's default 20.000000. Returns the parameter, to wrap its `new`.
inline QgsProcessingParameterNumber* decimals(int places, QgsProcessingParameterNumber* parameter) {
  QVariantMap metadata = parameter->metadata();
  QVariantMap wrapper = metadata.value(QStringLiteral("widget_wrapper")).toMap();
  wrapper.insert(QStringLiteral("decimals"), places);
  metadata.insert(QStringLiteral("widget_wrapper"), wrapper);
  parameter->setMetadata(metadata);
  return parameter;
}

}  // namespace tinlod::qgis
