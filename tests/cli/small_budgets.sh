# Sourced by the CLI tests that render every technique: smaller budgets than the defaults keep them
# quick; the code paths are the same. Sets the array `small` for technique $1.
small_budgets() {
  # Every technique's direct pass: the moving-light Cornell box's 64 emitter samples each render a
  # cube shadow map, 256^2 a face by default (0.4 s of a 1.1 s render at 40 x 24); 64^2 runs the same
  # code.
  small=(--set shadow.cubeSize=64)
  case "$1" in
    # LightSkin's RSM is 1024^2 by default, per layer: the moving-light Cornell box has 11 (the point
    # light's six cube faces, the emissive panel's five), and lightskin-full shades every texel of
    # them at every cache.
    lightskin) small+=(--set rsm.size=128) ;;
    # The BRSM importance: every texel of 11 layers x 256 view lights. N = 256 lights instead of 1024:
    # the imperfect shadow maps with planes (two splats, gap filling) took 1.4 s of a 1.5 s frame.
    vsgl|vpl-brsm|tcas) small+=(--set rsm.size=64 --set "$1.count=256") ;;
    lightskin-full) small+=(--set rsm.size=32) ;; # 3.9 s a 3-frame render at 40 x 24, 8.7 s at 64
    # The sampler's 100 warm-up frames run the per-frame code 100 times before the first frame; 10
    # run it too (0.7 s less a render here, more under ASan).
    smcir|smcir-rt) small+=(--set smcir.vplCount=256 --set smcir.warmupIterations=10) ;;
    ir|mir) small+=(--set "$1.vplCount=256") ;;
  esac
}
