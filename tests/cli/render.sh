#!/usr/bin/env bash
# Headless renders end to end: every built-in scene writes a non-black PNG, EXR output is linear,
# the same settings give the same image, and scene files and glTF files work as --scene.
set -eu
vplgi="$1"
shared="${2:-}"
here="$(cd "$(dirname "$0")/../.." && pwd)"
. "$here/tests/cli/shared_assets.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

mean_of() { # mean byte value of a PNG's RGB via a tiny python3 reader (zlib + filters)
  python3 - "$1" <<'PY'
import sys, zlib, struct
data = open(sys.argv[1], 'rb').read()
assert data[:8] == b'\x89PNG\r\n\x1a\n'
pos, idat, w, h = 8, b'', 0, 0
while pos < len(data):
    n, kind = struct.unpack('>I4s', data[pos:pos+8]); body = data[pos+8:pos+8+n]; pos += 12 + n
    if kind == b'IHDR': w, h, depth, ctype = struct.unpack('>IIBB', body[:10]); assert depth == 8 and ctype == 6
    if kind == b'IDAT': idat += body
raw = zlib.decompress(idat); stride = w * 4; prev = bytearray(stride); total = 0; i = 0
for y in range(h):
    f = raw[i]; line = bytearray(raw[i+1:i+1+stride]); i += 1 + stride
    for x in range(stride):
        a = line[x-4] if x >= 4 else 0; b = prev[x]; c = prev[x-4] if x >= 4 else 0
        if f == 1: line[x] = (line[x] + a) & 255
        elif f == 2: line[x] = (line[x] + b) & 255
        elif f == 3: line[x] = (line[x] + (a + b) // 2) & 255
        elif f == 4:
            p = a + b - c; pa, pb, pc = abs(p-a), abs(p-b), abs(p-c)
            line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    total += sum(v for k, v in enumerate(line) if k % 4 != 3); prev = line
print(total / (w * h * 3))
PY
}

for scene in caustics cornell furnace glossy maze street; do
  "$vplgi" render --scene "$scene" --width 96 --height 64 --out "$work/$scene.png" --quiet > "$work/$scene.log"
  grep -q "$work/$scene.png" "$work/$scene.log"
  mean=$(mean_of "$work/$scene.png")
  echo "$scene: mean display value $mean"
  python3 -c "import sys; sys.exit(0 if float('$mean') > 8 else 1)" || { echo "FAIL: $scene is black"; exit 1; }
done

# Same seed and settings -> the same bytes.
"$vplgi" render --scene cornell --width 64 --height 48 --out "$work/a.png" --quiet >/dev/null
"$vplgi" render --scene cornell --width 64 --height 48 --out "$work/b.png" --quiet >/dev/null
cmp "$work/a.png" "$work/b.png"

# EXR output and scene files.
"$vplgi" render --scene "$here/scenes/cornell.json" --width 64 --height 48 --out "$work/c.exr" --quiet \
  --set smcir.vplCount=256 --set smcir.warmupIterations=5 >/dev/null # its technique (smcir), made cheap
test -s "$work/c.exr"
"$vplgi" render --scene "$here/scenes/maze.json" --frames 3 --width 64 --height 48 --out "$work/m.png" --quiet >/dev/null
test -s "$work/m.png"

# The RSM techniques from their scene files (vsgl), small: indirect light on the floor, each debug
# view of vsgl written and different from the final image.
"$vplgi" render --scene "$here/scenes/caustics.json" --width 64 --height 48 --set rsm.size=64 --set vsgl.count=128 \
  --set renderer.display=indirect --out "$work/vsgl-indirect.png" --quiet >/dev/null
mean=$(mean_of "$work/vsgl-indirect.png")
echo "caustics, vsgl indirect: mean display value $mean"
python3 -c "import sys; sys.exit(0 if float('$mean') > 2 else 1)" || { echo "FAIL: vsgl's indirect light is black"; exit 1; }
"$vplgi" render --scene "$here/scenes/caustics.json" --width 64 --height 48 --set rsm.size=64 --set vsgl.count=128 \
  --out "$work/vsgl-final.png" --quiet >/dev/null
for view in vsgl.rsm vsgl.rsmNormal vsgl.importance vsgl.viewLights vsgl.ism vsgl.cancellation; do
  "$vplgi" render --scene "$here/scenes/caustics.json" --width 64 --height 48 --set rsm.size=64 --set vsgl.count=128 \
    --set renderer.display=$view --out "$work/view-$view.png" --quiet >/dev/null
  if cmp -s "$work/vsgl-final.png" "$work/view-$view.png"; then echo "FAIL: display=$view shows the final image"; exit 1; fi
done
"$vplgi" render --scene "$here/scenes/caustics.json" --technique vpl-brsm --width 64 --height 48 --set rsm.size=64 \
  --set vpl-brsm.count=128 --out "$work/vpl-brsm.png" --quiet >/dev/null
test -s "$work/vpl-brsm.png"
# LightSkin from its scene file (the canyon, coarse caches and a small RSM): indirect light on the
# shaded facades, each debug view written and different from the final image.
lightskin=(--scene "$here/scenes/canyon.json" --width 64 --height 36 --set rsm.size=64 --set lightskin.cacheDistance=8)
"$vplgi" render "${lightskin[@]}" --set renderer.display=indirect --out "$work/lightskin-indirect.png" --quiet >/dev/null
mean=$(mean_of "$work/lightskin-indirect.png")
echo "canyon, lightskin indirect: mean display value $mean"
python3 -c "import sys; sys.exit(0 if float('$mean') > 2 else 1)" || { echo "FAIL: lightskin's indirect light is black"; exit 1; }
"$vplgi" render "${lightskin[@]}" --out "$work/lightskin-final.png" --quiet >/dev/null
for view in lightskin.rsm lightskin.caches lightskin.importance lightskin.selected; do
  "$vplgi" render "${lightskin[@]}" --set renderer.display=$view --out "$work/view-$view.png" --quiet >/dev/null
  if cmp -s "$work/lightskin-final.png" "$work/view-$view.png"; then echo "FAIL: display=$view shows the final image"; exit 1; fi
done

# Each debug view (renderer.display) writes that view: every one differs from the final image.
for view in direct albedo normal depth; do
  "$vplgi" render --scene cornell --width 48 --height 48 --set renderer.display=$view --out "$work/view-$view.png" --quiet >/dev/null
done
"$vplgi" render --scene cornell --width 48 --height 48 --out "$work/a48.png" --quiet >/dev/null
for view in albedo normal depth; do
  if cmp -s "$work/a48.png" "$work/view-$view.png"; then echo "FAIL: display=$view shows the final image"; exit 1; fi
done
cmp "$work/a48.png" "$work/view-direct.png" # the direct technique: direct view = final image
if "$vplgi" render --scene cornell --set renderer.display=bogus --out "$work/bogus.png" 2>"$work/bogus.err"; then
  echo "FAIL: renderer.display=bogus accepted"; exit 1
fi
grep -q 'renderer.display' "$work/bogus.err"; test ! -e "$work/bogus.png"
grep -q 'shadow.point' "$work/bogus.err" # the error lists the texture views too
# A texture view (the renderer's shadow cubes, every layer tiled) and one layer of it.
"$vplgi" render --scene cornell --width 48 --height 48 --set renderer.display=shadow.point --out "$work/view-shadow.png" --quiet >/dev/null
"$vplgi" render --scene cornell --width 48 --height 48 --set renderer.display=shadow.point --set renderer.displayLayer=3 --out "$work/view-shadow3.png" --quiet >/dev/null
if cmp -s "$work/a48.png" "$work/view-shadow.png" || cmp -s "$work/view-shadow.png" "$work/view-shadow3.png"; then
  echo "FAIL: display=shadow.point shows the final image or ignores renderer.displayLayer"; exit 1
fi
echo "display views: ok"

# A glTF file as --scene (from the shared assets: skipped when absent, failed when CI=true).
if find_shared_asset scenes/cornell-box/CornellBox.glb "$shared"; then
  "$vplgi" render --scene "$shared_asset_path" --width 64 --height 48 --out "$work/g.png" --quiet >/dev/null
  mean=$(mean_of "$work/g.png"); echo "CornellBox.glb: mean display value $mean"
  python3 -c "import sys; sys.exit(0 if float('$mean') > 8 else 1)"
fi
echo "render checks passed"

# Every EGL platform of the headless context works on its own (the fallbacks are real).
for platform in surfaceless device pbuffer; do
  # The pbuffer fallback uses the default display: Mesa picks the surfaceless platform for it
  # when EGL_PLATFORM says so (or X under Xvfb).
  out=$(EGL_PLATFORM=surfaceless VPLGI_EGL_PLATFORM=$platform "$vplgi" render --scene cornell --width 32 --height 32 --out "$work/p.png" 2>&1)
  echo "$out" | grep -q "context = EGL $platform" || { echo "FAIL: EGL $platform"; echo "$out" | tail -3; exit 1; }
  echo "EGL $platform: ok"
done
echo "all render checks passed"
