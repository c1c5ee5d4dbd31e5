# SPDX-License-Identifier: GPL-3.0-or-later
# A Debian package of the command line and the QGIS plugin: `cpack -G DEB` in the build
# folder (scripts/package.sh). Its dependencies come from dpkg-shlibdeps, so it is pinned
# to the libraries, QGIS's exact libqgis_core among them, that it was built against.
install(TARGETS tinlod RUNTIME DESTINATION bin)
# The Dask tile driver: bin/tinlod-tiles finds its modules in share/tinlod/tiles.
install(PROGRAMS ${TILES_SCRIPT} DESTINATION bin RENAME tinlod-tiles)
install(FILES ${TILES_MODULES} DESTINATION share/tinlod/tiles/tinlodtiles)
if(TINLOD_WITH_QGIS)
  # Where Debian's QGIS keeps its system-wide Python plugins (QgsApplication::pkgDataPath()).
  set(TINLOD_QGIS_PLUGIN_DIR share/qgis/python/plugins/tinlod)
  install(TARGETS tinlod_processing LIBRARY DESTINATION ${TINLOD_QGIS_PLUGIN_DIR})
  install(FILES ${PLUGIN_SOURCES} DESTINATION ${TINLOD_QGIS_PLUGIN_DIR})
  install(FILES ${PLUGIN_HELP_PAGES} DESTINATION ${TINLOD_QGIS_PLUGIN_DIR}/help)
  install(DIRECTORY ${HELP_HTML_DIR} DESTINATION ${TINLOD_QGIS_PLUGIN_DIR}/help)
endif()
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION share/doc/tinlod)
# The README's links lead into docs/.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs DESTINATION share/doc/tinlod)
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION share/doc/tinlod RENAME copyright)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME tinlod)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Simplified, hierarchical TINs from raster DEMs (command line and QGIS plugin)")
set(CPACK_PACKAGE_CONTACT "tinlod developers")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The plugin needs QGIS's Python side too, which no shared library names.
if(TINLOD_WITH_QGIS)
  set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3-qgis")
endif()
# tinlod-tiles runs on Debian's Python with GDAL's bindings and Dask; the rest of tinlod
# works without them.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "python3-gdal, python3-numpy, python3-distributed")
include(CPack)
