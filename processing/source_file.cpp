// SPDX-License-Identifier: GPL-3.0-or-later
#include "source_file.h"

#include <qgsexception.h>
#include <qgsprocessingutils.h>
#include <qgsvectorfilewriter.h>

#include <memory>

#include "parameter_given.h"

namespace tinlod::qgis {

std::string sourceFile(const QgsProcessingParameterDefinition* definition, const QVariantMap& parameters,
                       QgsProcessingContext& context, QgsProcessingFeedback* feedback, const QString& kind) {
  const QString name = definition->name();
  std::unique_ptr<QgsProcessingFeatureSource> source(QgsProcessingParameters::parameterAsSource(definition, parameters, context));
  if (!source) {
    if (!parameterGiven(parameters, name) && (definition->flags() & QgsProcessingParameterDefinition::FlagOptional)) return {};
    throw QgsProcessingException(QStringLiteral("%1: choose %2 (a layer on the map or a file)").arg(name, kind));
  }
  QString layerName;
  const QString path = QgsProcessingParameters::parameterAsCompatibleSourceLayerPathAndLayerName(
      definition, parameters, context, QgsVectorFileWriter::supportedFormatExtensions(), QStringLiteral("gpkg"), feedback,
      &layerName);
  if (path.isEmpty()) throw QgsProcessingException(QStringLiteral("%1: QGIS could not write %2 to a file for tinlod").arg(name, kind));
  return (layerName.isEmpty() ? path : path + QStringLiteral("|layername=") + layerName).toStdString();
}

}  // namespace tinlod::qgis
