// SPDX-License-Identifier: GPL-3.0-or-later
// The C entry points the Python plugin calls through ctypes: qgis_process 3.22 loads
// only Python plugins, so the provider is registered from C++ on their behalf.
#include <qgsapplication.h>
#include <qgsprocessingregistry.h>

#include "provider.h"
#include "tinlod/allocator_policy.h"

namespace {
tinlod::qgis::Provider* gProvider = nullptr;  // owned by the registry while registered
}

extern "C" __attribute__((visibility("default"))) int tinlod_register_provider() {
  if (gProvider) return 1;
  // qgis_process runs one algorithm and ends, as the command line does: large builds get
  // the command line's allocator policy. The desktop's allocator is left as it is.
  if (QgsApplication::platform() == QLatin1String("qgis_process")) tinlod::mapLargeArraysApart();
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
