// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <QString>

namespace tinlod::qgis {

// The URL of an algorithm's reference page (docs/qgis/<name>.md), shipped in the help/
// folder beside the provider's library (the plugin folder, the package's); empty when it
// is not there. The dialog's Help button opens it.
QString helpPageUrl(const QString& algorithmName);

}  // namespace tinlod::qgis
