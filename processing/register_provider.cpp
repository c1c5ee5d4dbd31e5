// SPDX-License-Identifier: GPL-3.0-or-later
// The C entry points the Python plugin calls through ctypes: qgis_process 3.22 loads
// only Python plugins, so the provider is registered from C++ on their behalf.
#include <qgsapplication.h>
#include <qgsprocessingregistry.h>

#include <QCoreApplication>

#include "provider.h"
#include "tinlod/allocator_policy.h"
#include "tinlod/stop_signals.h"

namespace {
tinlod::qgis::Provider* gProvider = nullptr;  // owned by the registry while registered

// Whether this qgis_process was started to run a tinlod algorithm ("run tinlod:buildhierarchy").
bool runningATinlodAlgorithm() {
  const QStringList arguments = QCoreApplication::arguments();
  const int run = arguments.indexOf(QStringLiteral("run"));
  return run >= 0 && run + 1 < arguments.size() && arguments[run + 1].startsWith(QStringLiteral("tinlod:"));
}
}  // namespace

extern "C" __attribute__((visibility("default"))) int tinlod_register_provider() {
  if (gProvider) return 1;
  // qgis_process runs one algorithm and ends, as the command line does: large builds get
  // the command line's allocator policy. The desktop's allocator is left as it is.
  if (QgsApplication::platform() == QLatin1String("qgis_process")) tinlod::mapLargeArraysApart();
  // A Ctrl-C between now and the algorithm's start (qgis_process's first second) was lost:
  // ignored in a script's background job, only noted by Python's handler in a terminal, and
  // the run went on to replace its outputs. Caught from here, it stops the run as a later
  // one does (the algorithm's feedback releases the signals when it ends).
  if (QgsApplication::platform() == QLatin1String("qgis_process") && runningATinlodAlgorithm())
    tinlod::catchStopSignals();
  auto* provider = new tinlod::qgis::Provider();
  if (!QgsApplication::processingRegistry()->addProvider(provider)) {
    delete provider;  // refused (an id clash): the registry did not take it
    return 0;
  }
  gProvider = provider;
  return 1;
}

extern "C" __attribute__((visibility("default"))) void tinlod_unregister_provider() {
  if (!gProvider) return;
  QgsApplication::processingRegistry()->removeProvider(gProvider);  // deletes it
  gProvider = nullptr;
}
