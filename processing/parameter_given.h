// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <QVariantMap>

namespace tinlod::qgis {

// Whether a parameter is set at all: a layer, source or point object from the dialog or
// PyQGIS reads as an empty string, so the variant itself is tested, not its text.
inline bool parameterGiven(const QVariantMap& parameters, const QString& name) {
  const QVariant v = parameters.value(name);
  return v.isValid() && !v.isNull() && !(v.type() == QVariant::String && v.toString().isEmpty());
}

}  // namespace tinlod::qgis
