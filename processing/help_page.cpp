// SPDX-License-Identifier: GPL-3.0-or-later
#include "help_page.h"

#include <dlfcn.h>

#include <QFileInfo>
#include <QUrl>

namespace tinlod::qgis {

QString helpPageUrl(const QString& algorithmName) {
  // Wherever the plugin was installed: the folder of the library this code is in.
  Dl_info info;
  if (!dladdr(reinterpret_cast<void*>(&helpPageUrl), &info) || !info.dli_fname) return {};
  const QString page =
      QFileInfo(QString::fromLocal8Bit(info.dli_fname)).absolutePath() + QStringLiteral("/help/%1.md").arg(algorithmName);
  return QFileInfo::exists(page) ? QUrl::fromLocalFile(page).toString() : QString();
}

}  // namespace tinlod::qgis
