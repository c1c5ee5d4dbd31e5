// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <QIcon>
#include <QString>

namespace tinlod::qgis {

// The provider's icon, and one per group of algorithms (construction, accuracy, use,
// lines), as SVGs compiled into the provider's library (icons.qrc).
QIcon providerIcon();
QIcon groupIcon(const QString& groupId);

}  // namespace tinlod::qgis
