#!/usr/bin/env bash
# Builds everything and runs every test (unit, real DEMs from ../shared/data when present,
# command line, QGIS Processing headless, qgis_process).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/build.sh"
cd "$root/build"
ctest --output-on-failure -j "$(nproc)"
