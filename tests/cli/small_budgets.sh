# Sourced by the CLI tests that render every technique: smaller budgets than the defaults keep them
# quick; the code paths are the same. Sets the array `small` for technique $1.
small_budgets() {
  small=()
  case "$1" in
    lightskin-full) small=(--set rsm.size=128) ;; # shades every RSM texel at every cache
    smcir|ir) small=(--set "$1.vplCount=256") ;;
    smcir-rt) small=(--set smcir.vplCount=256) ;;
  esac
}
