#!/usr/bin/env bash
# OpenImageIO is loaded on the first image vplgi reads or writes, not at start (core/util/image_codec.h:
# linking it cost every process 0.4 s before main). Checks, with the dynamic loader's own log
# (LD_DEBUG=files names every object it loads):
#  - vplgi does not link it (DT_NEEDED), and `vplgi scenes` never loads it;
#  - a render to PNG does load it, through the module, and writes the image (so the log check can fail);
#  - a copied binary with a broken module beside it falls back to the build's module, silently.
set -u
vplgi="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures+1)); }

if readelf -d "$vplgi" | grep NEEDED | grep -q OpenImageIO; then fail "vplgi links OpenImageIO directly"; fi
LD_DEBUG=files "$vplgi" scenes > "$work/scenes.out" 2> "$work/scenes.log" || fail "vplgi scenes failed"
grep -q "file=.*libOpenImageIO" "$work/scenes.log" && fail "vplgi scenes loaded OpenImageIO"

LD_DEBUG=files "$vplgi" render --scene cornell --width 16 --height 16 --out "$work/a.png" --quiet \
  > /dev/null 2> "$work/render.log" || fail "the render failed: $(grep -v '^ *[0-9]*:' "$work/render.log" | head -3)"
[ -s "$work/a.png" ] || fail "the render wrote no PNG"
grep -q "file=.*libvplgi_image_oiio.so" "$work/render.log" || fail "the render did not load the image module"
grep -q "file=.*libOpenImageIO" "$work/render.log" || fail "the render did not load OpenImageIO"

# A module beside the executable comes first; one that does not load is passed over.
mkdir "$work/copy"
cp "$vplgi" "$work/copy/vplgi"
echo "not a shared object" > "$work/copy/libvplgi_image_oiio.so"
if "$work/copy/vplgi" render --scene cornell --width 16 --height 16 --out "$work/b.png" --quiet > "$work/copy.log" 2>&1; then
  [ -s "$work/b.png" ] || fail "the copied binary wrote no PNG"
else
  fail "the copied binary with a broken module beside it failed: $(head -3 "$work/copy.log")"
fi
echo "$failures failures"
[ "$failures" -eq 0 ]
