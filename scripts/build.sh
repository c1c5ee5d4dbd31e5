#!/usr/bin/env bash
# Installs what is missing, then configures and builds everything into build/
# (the command line, the QGIS provider, the plugin folder and zip, tests, benchmarks).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/install-deps.sh"
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$root/build" -j "$(nproc)"
