// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <QString>

#include <qgsprocessingalgorithm.h>

namespace tinlod::qgis {

// The URL of an algorithm's reference page (docs/qgis/<name>.md), shipped in the help/
// folder beside the provider's library (the plugin folder, the package's), as HTML
// (help/html/qgis/<name>.html, with the rest of the reference) or else as Markdown; empty
// when it is not there. The dialog's Help button opens it.
QString helpPageUrl(const QString& algorithmName);

// Gives each parameter of `algorithm` its row's description in the Parameters table of its
// reference page as help (the dialog's tooltip): the page is the one source, which the docs
// test holds to the definitions. Nothing when the page is not there.
void addParameterHelp(QgsProcessingAlgorithm& algorithm);

}  // namespace tinlod::qgis
