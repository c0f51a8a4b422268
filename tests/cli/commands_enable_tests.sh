#!/usr/bin/env bash
# The README's two commands in either order configure the tests: a scratch build directory is
# configured with scripts/run's cmake line, then scripts/test's (and the other way round), and must
# have the tests switched on and registered with ctest. Configure only (VPLGI_CONFIGURE_ONLY=1): no
# second build. The original bug: scripts/run configured -DVPLGI_BUILD_TESTS=OFF into build/, then
# scripts/test reconfigured the same directory without the option and ctest found no tests, exit 0.
set -euo pipefail
here="$(cd "$(dirname "$0")/../.." && pwd)"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

check() { # check <build dir> <what>
  grep -q '^VPLGI_BUILD_TESTS:BOOL=ON$' "$1/CMakeCache.txt" \
    || { echo "FAIL: $2: VPLGI_BUILD_TESTS is not ON"; grep VPLGI_BUILD_TESTS "$1/CMakeCache.txt"; exit 1; }
  # The tests that add_test registers at configure time (the Catch2 ones appear after a build).
  (cd "$1" && ctest -N) > "$work/list" 2>&1
  grep -q 'cli: bad input' "$work/list" || { echo "FAIL: $2: ctest lists no tests"; cat "$work/list"; exit 1; }
  echo "ok: $2: tests on, $(grep -c 'Test *#' "$work/list") registered before the build"
}

export VPLGI_CONFIGURE_ONLY=1
VPLGI_BUILD_DIR="$work/a" "$here/scripts/run"
VPLGI_BUILD_DIR="$work/a" "$here/scripts/test"
check "$work/a" "scripts/run, then scripts/test"
VPLGI_BUILD_DIR="$work/b" "$here/scripts/test"
VPLGI_BUILD_DIR="$work/b" "$here/scripts/run"
check "$work/b" "scripts/test, then scripts/run"
# A build directory configured with the tests off (as scripts/run did) is switched back on.
cmake -S "$here" -B "$work/c" -DVPLGI_BUILD_TESTS=OFF > /dev/null
VPLGI_BUILD_DIR="$work/c" "$here/scripts/test"
check "$work/c" "an old build directory with the tests off, then scripts/test"
