// SPDX-License-Identifier: GPL-3.0-or-later
#include "group_icon.h"

namespace tinlod::qgis {

QIcon providerIcon() { return QIcon(QStringLiteral(":/tinlod/provider.svg")); }

QIcon groupIcon(const QString& groupId) { return QIcon(QStringLiteral(":/tinlod/%1.svg").arg(groupId)); }

}  // namespace tinlod::qgis
