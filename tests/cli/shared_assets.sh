# Sourced by CLI tests that need the shared test assets: the shell twin of tests/common/shared_assets.h.
#
# find_shared_asset RELATIVE DEFAULT_DIR
#   The shared assets are in $VPLGI_SHARED_DIR when it is set and not empty, else in DEFAULT_DIR (the
#   build's VPLGI_SHARED_DIR, passed in by ctest). When RELATIVE exists there, sets
#   shared_asset_path to it and returns 0. When it does not: with CI=true prints FAIL and exits the
#   test with status 1 (CI always has ../shared); otherwise prints "skipped: ..." and returns 1.
#   Call it directly (not in $(...)), so that the exit ends the test.
find_shared_asset() {
  local dir="${VPLGI_SHARED_DIR:-${2:-}}"
  shared_asset_path="$dir/$1"
  if [ -n "$dir" ] && [ -e "$shared_asset_path" ]; then return 0; fi
  if [ "${CI:-}" = "true" ]; then
    echo "FAIL: $shared_asset_path is absent and CI=true: shared assets are required in CI (set VPLGI_SHARED_DIR)"
    exit 1
  fi
  echo "skipped: $shared_asset_path is absent (set VPLGI_SHARED_DIR to the shared assets)"
  return 1
}
