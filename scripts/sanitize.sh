#!/usr/bin/env bash
# Builds everything with AddressSanitizer and UndefinedBehaviorSanitizer (float-cast-overflow
# included, which -fsanitize=undefined leaves out) into build-asan/, apart from the normal
# build/, and runs the whole test suite under them. A finding stops the test it is in, which
# fails. Leaks that third-party libraries (QGIS, Qt, GDAL, PROJ, fontconfig, Python) leave at
# exit are suppressed by tests/sanitizer/lsan.supp; tinlod's own code has no suppression.
#
# Usage: scripts/sanitize.sh [ctest arguments, e.g. -R ReaderFuzz]
# With TINLOD_BUILD_LOCK=/path/to/lockfile the build and the tests run under flock on it, for
# machines where several builds share the cores.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build="$root/build-asan"
sanitizers="-fsanitize=address,undefined -fsanitize=float-cast-overflow"

locked() {
  if [[ -n ${TINLOD_BUILD_LOCK:-} ]]; then flock "$TINLOD_BUILD_LOCK" "$@"; else "$@"; fi
}

bash "$root/scripts/install-deps.sh"
# RelWithDebInfo: optimised as users run it, with line numbers in the reports.
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS="$sanitizers -fno-omit-frame-pointer" \
  -DCMAKE_EXE_LINKER_FLAGS="$sanitizers" -DCMAKE_SHARED_LINKER_FLAGS="$sanitizers" \
  -DTINLOD_SANITIZE=ON > /dev/null
locked cmake --build "$build" -j "$(nproc)"

export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:suppressions=$root/tests/sanitizer/ubsan.supp"
export LSAN_OPTIONS="suppressions=$root/tests/sanitizer/lsan.supp:print_suppressions=0"
cd "$build"
start=$SECONDS
locked ctest --output-on-failure -j "$(nproc)" -LE qgis "$@"
# QGIS's own leaks (label qgis: the Processing tests in a QgsApplication) are told apart by
# the QGIS functions on their allocation stacks, which only the slow unwinder finds through
# Qt's frames, built without frame pointers; it makes these tests five times slower.
ASAN_OPTIONS="$ASAN_OPTIONS:fast_unwind_on_malloc=0" locked ctest --output-on-failure -j "$(nproc)" -L qgis "$@"
echo "sanitize.sh: the suite passed under ASan and UBSan in $(((SECONDS - start) / 60)) min"
