// SPDX-License-Identifier: GPL-3.0-or-later
#include "stale_layers.h"

#include <qgslayertree.h>
#include <qgsmaplayer.h>
#include <qgsproject.h>
#include <qgsproviderregistry.h>
#include <qgsprovidersublayerdetails.h>

#include <QDateTime>
#include <QFileInfo>
#include <QRegularExpression>
#include <QSet>

#include "layer_placement.h"

namespace tinlod::qgis {
namespace {

struct Table {
  QString file;  // canonical, so that two spellings of one path match
  QString name;
};

Table tableOf(const QgsMapLayer* layer) {
  const QVariantMap parts = QgsProviderRegistry::instance()->decodeUri(layer->providerType(), layer->source());
  const QFileInfo file(parts.value(QStringLiteral("path")).toString());
  return {file.exists() ? file.canonicalFilePath() : file.absoluteFilePath(), parts.value(QStringLiteral("layerName")).toString()};
}

// A run loads a layer per level, each asking for its file's tables: the file is read once
// while it stays as it is (the same size and time), not once per layer.
QSet<QString> tablesIn(const QString& file) {
  struct Read {
    QString file;
    QDateTime modified;
    qint64 size = -1;
    QSet<QString> names;
  };
  static Read last;
  const QFileInfo info(file);
  if (last.file == file && last.modified == info.lastModified() && last.size == info.size()) return last.names;
  QSet<QString> names;
  for (const QgsProviderSublayerDetails& sublayer : QgsProviderRegistry::instance()->querySublayers(file))
    names.insert(sublayer.name());
  last = {file, info.lastModified(), info.size(), names};
  return names;
}

int levelOf(const QString& table) {
  static const QRegularExpression level(QStringLiteral("^level_(\\d+)$"));
  const QRegularExpressionMatch match = level.match(table);
  return match.hasMatch() ? match.captured(1).toInt() : -1;
}

// The layer tree node of the coarsest level of `file` in the project, if any.
QgsLayerTreeLayer* coarsestLevel(QgsProject* project, const QString& file) {
  QgsLayerTreeLayer* coarsest = nullptr;
  int best = -1;
  for (QgsLayerTreeLayer* node : project->layerTreeRoot()->findLayers()) {
    if (!node->layer() || !loadedByARun(node->layer())) continue;
    const Table table = tableOf(node->layer());
    if (table.file == file && levelOf(table.name) > best) {
      best = levelOf(table.name);
      coarsest = node;
    }
  }
  return coarsest;
}

}  // namespace

void removeLayersOfTablesGone(QgsMapLayer* layer, QgsProject* project) {
  if (!layer || !project || layer->providerType() != QLatin1String("ogr")) return;
  const QString file = tableOf(layer).file;
  const QSet<QString> tables = tablesIn(file);
  if (tables.isEmpty()) return;  // unreadable: nothing is known to be gone
  QStringList gone;
  bool shownGone = false;
  for (QgsMapLayer* other : project->mapLayers()) {
    if (other == layer || other->providerType() != QLatin1String("ogr") || !loadedByARun(other)) continue;
    const Table table = tableOf(other);
    if (table.file != file || table.name.isEmpty() || tables.contains(table.name)) continue;
    gone << other->id();
    const QgsLayerTreeLayer* node = project->layerTreeRoot()->findLayer(other);
    shownGone = shownGone || (node && node->itemVisibilityChecked());
  }
  if (gone.isEmpty()) return;
  project->removeMapLayers(gone);
  if (QgsLayerTreeLayer* coarsest = shownGone ? coarsestLevel(project, file) : nullptr) coarsest->setItemVisibilityChecked(true);
}

}  // namespace tinlod::qgis
