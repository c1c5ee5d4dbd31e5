# shellcheck shell=bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Sourced by the shell tests: their pass/fail lines and an isolated QGIS profile, so that
# the user's own profile is never touched and every test reports the same way.

passes=0
failures=0
check() {  # check DESCRIPTION COMMAND...: passes when the command succeeds
  local what=$1; shift
  if "$@"; then echo "ok: $what"; passes=$((passes + 1)); else echo "FAILED: $what"; failures=$((failures + 1)); fi
}

# finish_checks NAME: the summary line, and the exit status the test ends with.
finish_checks() {
  echo "$1: $passes passed, $failures failed"
  exit $((failures > 0))
}

# isolated_qgis WORK [PLUGIN_DIR]: qgis_process.bin (as $qp) with a fresh configuration
# under WORK, headless, and the plugin copied into its default profile and enabled; without
# PLUGIN_DIR only enabled, for a plugin found elsewhere (QGIS_PLUGINPATH).
isolated_qgis() {
  local work=$1 plugin=${2:-}
  export QGIS_CUSTOM_CONFIG_PATH=$work/config QT_QPA_PLATFORM=offscreen HOME=$work XDG_RUNTIME_DIR=$work/xdg
  mkdir -p "$QGIS_CUSTOM_CONFIG_PATH/profiles/default/python/plugins"
  mkdir -m 700 "$XDG_RUNTIME_DIR"
  [[ -z $plugin ]] || cp -r "$plugin" "$QGIS_CUSTOM_CONFIG_PATH/profiles/default/python/plugins/tinlod"
  qp=/usr/bin/qgis_process.bin
  "$qp" plugins enable tinlod > /dev/null 2>&1 || true
}
