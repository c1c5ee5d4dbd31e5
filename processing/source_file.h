// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <qgsprocessingcontext.h>
#include <qgsprocessingfeedback.h>
#include <qgsprocessingparameters.h>

#include <string>

namespace tinlod::qgis {

// The file the core reads a vector input from with GDAL ("path|layername=name"), or ""
// when an optional input is not given. A layer stored in a file GDAL reads goes as it is;
// any other source (a memory or database layer, "Selected features only", a feature limit)
// is first written by QGIS to a temporary GeoPackage, QGIS's own way of handing a source
// to a tool that reads files. Throws QgsProcessingException naming the parameter; `kind`
// says what is wanted ("a point layer").
std::string sourceFile(const QgsProcessingParameterDefinition* definition, const QVariantMap& parameters,
                       QgsProcessingContext& context, QgsProcessingFeedback* feedback, const QString& kind);

}  // namespace tinlod::qgis
