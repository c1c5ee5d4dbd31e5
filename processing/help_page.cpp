// SPDX-License-Identifier: GPL-3.0-or-later
#include "help_page.h"

#include <dlfcn.h>

#include <QFile>
#include <QFileInfo>
#include <QMap>
#include <QRegularExpression>
#include <QUrl>

namespace tinlod::qgis {

namespace {

// Wherever the plugin was installed: the folder of the library this code is in.
QString pagePath(const QString& algorithmName) {
  Dl_info info;
  if (!dladdr(reinterpret_cast<void*>(&helpPageUrl), &info) || !info.dli_fname) return {};
  return QFileInfo(QString::fromLocal8Bit(info.dli_fname)).absolutePath() + QStringLiteral("/help/%1.md").arg(algorithmName);
}

// A table cell's Markdown as a tooltip's plain text: no code marks, links as their text.
QString plainText(QString cell) {
  static const QRegularExpression link(QStringLiteral("\\[([^\\]]*)\\]\\([^)]*\\)"));
  cell.replace(link, QStringLiteral("\\1"));
  cell.remove(QLatin1Char('`'));
  cell.remove(QStringLiteral("**"));
  static const QRegularExpression emphasis(QStringLiteral("\\*([^*]+)\\*"));
  cell.replace(emphasis, QStringLiteral("\\1"));
  cell.replace(QStringLiteral("\\|"), QStringLiteral("|"));
  return cell.trimmed();
}

// The Parameters table's rows: name -> description (the last cell).
QMap<QString, QString> parameterRows(const QString& path) {
  QFile file(path);
  QMap<QString, QString> rows;
  if (!file.open(QIODevice::ReadOnly | QIODevice::Text)) return rows;
  static const QRegularExpression row(QStringLiteral("^\\| `([A-Z][A-Z0-9_]*)` \\|"));
  bool inParameters = false;
  for (const QString& line : QString::fromUtf8(file.readAll()).split(QLatin1Char('\n'))) {
    if (line.startsWith(QStringLiteral("## "))) inParameters = line.trimmed() == QStringLiteral("## Parameters");
    const QRegularExpressionMatch m = row.match(line);
    if (!inParameters || !m.hasMatch()) continue;
    // The description is the last cell: after the last " | " that is not an escaped pipe.
    QString body = line.trimmed();
    body.chop(1);  // the closing |
    body.replace(QStringLiteral("\\|"), QStringLiteral("\x01"));
    QString description = body.section(QStringLiteral(" | "), -1);
    description.replace(QLatin1Char('\x01'), QStringLiteral("\\|"));
    rows.insert(m.captured(1), plainText(description));
  }
  return rows;
}

}  // namespace

QString helpPageUrl(const QString& algorithmName) {
  const QString page = pagePath(algorithmName);
  if (page.isEmpty()) return {};
  // The HTML page where it was made (its links lead on to the rest of the reference).
  const QString html = QFileInfo(page).absolutePath() + QStringLiteral("/html/qgis/%1.html").arg(algorithmName);
  if (QFileInfo::exists(html)) return QUrl::fromLocalFile(html).toString();
  return QFileInfo::exists(page) ? QUrl::fromLocalFile(page).toString() : QString();
}

void addParameterHelp(QgsProcessingAlgorithm& algorithm) {
  const QString page = pagePath(algorithm.name());
  if (page.isEmpty()) return;
  const QMap<QString, QString> rows = parameterRows(page);
  for (auto it = rows.begin(); it != rows.end(); ++it)
    // Made by the algorithm's own initAlgorithm, not const: only handed out as const.
    if (auto* p = const_cast<QgsProcessingParameterDefinition*>(algorithm.parameterDefinition(it.key())))
      p->setHelp(it.value());
}

}  // namespace tinlod::qgis
