// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <qgsprocessingalgorithm.h>
#include <qgsprocessingcontext.h>
#include <qgsprocessingparameters.h>

#include <string>

namespace tinlod::qgis {

// HIERARCHY: a GeoPackage written by tinlod, chosen as a file or as any of its layers
// already on the map (a level, the triangles), as native algorithms take their inputs.
QgsProcessingParameterDefinition* hierarchyParameter(const QString& description);

// The GeoPackage file behind HIERARCHY; throws QgsProcessingException naming HIERARCHY
// when it is missing or not a layer of a GeoPackage file.
std::string hierarchyFile(const QgsProcessingParameterDefinition* definition, const QVariantMap& parameters,
                          QgsProcessingContext& context);

// checkParameterValues for an algorithm with a HIERARCHY: QGIS's checks, then hierarchyFile's,
// false with the message. Checked before the run, the message is the exception
// processing.run raises (a run's own error reaches only its log, the exception saying
// "There were errors executing the algorithm.").
bool parametersWithHierarchyAcceptable(const QgsProcessingAlgorithm& algorithm, const QVariantMap& parameters,
                                       QgsProcessingContext& context, QString* message);

}  // namespace tinlod::qgis
