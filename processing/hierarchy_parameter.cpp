// SPDX-License-Identifier: GPL-3.0-or-later
#include "hierarchy_parameter.h"

#include <qgsexception.h>
#include <qgsproviderregistry.h>
#include <qgsvectorlayer.h>

#include <QDir>
#include <QFileInfo>

#include "tinlod/hierarchy_info.h"

namespace tinlod::qgis {

QgsProcessingParameterDefinition* hierarchyParameter(const QString& description) {
  return new QgsProcessingParameterVectorLayer(QStringLiteral("HIERARCHY"), description,
                                               QList<int>() << QgsProcessing::TypeVectorAnyGeometry);
}

std::string hierarchyFile(const QgsProcessingParameterDefinition* definition, const QVariantMap& parameters,
                          QgsProcessingContext& context) {
  const QString wanted = QStringLiteral("choose a GeoPackage written by tinlod, or one of its layers on the map");
  QgsVectorLayer* layer = QgsProcessingParameters::parameterAsVectorLayer(definition, parameters, context);
  if (!layer) throw QgsProcessingException(QStringLiteral("HIERARCHY: ") + wanted);
  const QVariantMap parts = QgsProviderRegistry::instance()->decodeUri(layer->providerType(), layer->source());
  const QString path = parts.value(QStringLiteral("path")).toString();
  const QFileInfo file(path);
  // A level of a tinlod tiles catalogue (<stem>_levels/level_K.vrt): the catalogue is the input.
  const std::string catalogue = catalogueOfLevelFile(QDir::cleanPath(file.absoluteFilePath()).toStdString());
  if (!catalogue.empty())
    throw QgsProcessingException(QStringLiteral("HIERARCHY: '%1' is one level of a tinlod tiles catalogue: choose the catalogue "
                                                "itself, %2")
                                     .arg(layer->name(), QString::fromStdString(catalogue)));
  if (layer->providerType() != QLatin1String("ogr") || file.suffix().compare(QLatin1String("gpkg"), Qt::CaseInsensitive) != 0)
    throw QgsProcessingException(QStringLiteral("HIERARCHY: '%1' is not stored in a GeoPackage: %2").arg(layer->name(), wanted));
  return path.toStdString();
}

bool parametersWithHierarchyAcceptable(const QgsProcessingAlgorithm& algorithm, const QVariantMap& parameters,
                                       QgsProcessingContext& context, QString* message) {
  if (!algorithm.QgsProcessingAlgorithm::checkParameterValues(parameters, context, message)) return false;
  try {
    hierarchyFile(algorithm.parameterDefinition(QStringLiteral("HIERARCHY")), parameters, context);
  } catch (const QgsProcessingException& e) {
    if (message) *message = e.what();
    return false;
  }
  return true;
}

}  // namespace tinlod::qgis
