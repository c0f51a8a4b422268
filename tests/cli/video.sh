#!/usr/bin/env bash
# Videos through Debian's ffmpeg (issue 28 part 7), counted and compared by ffprobe/ffmpeg:
#   - `render --frames 12 --fps 24 --video v.mp4` gives 12 frames at 24/1, 0.5 s, and frame i of the
#     video is the PNG `--out f/%04d.png` wrote for frame i (an animated light: consecutive frames
#     differ, so a dropped or repeated frame would show);
#   - an odd size is padded to even, .mkv works, --out alone is then not written;
#   - the viewer's `video start/stop` (the M key) under Xvfb writes one frame per frame shown;
#   - bad extension, missing directory, no ffmpeg on PATH, an ffmpeg without libx264 and an ffmpeg that
#     fails: one error line, exit status 1, no file left behind.
set -eu
vplgi="$(realpath "$1")"
here="$(cd "$(dirname "$0")" && pwd)"
. "$here/lib.sh" # check, $work
command -v ffprobe >/dev/null || { echo "FAIL: ffmpeg is not installed (run ./scripts/deps)"; exit 1; }
probe() { # probe FILE -> "frames rate width height"
  ffprobe -v error -count_frames -select_streams v:0 \
    -show_entries stream=nb_read_frames,r_frame_rate,width,height -of csv=p=0 "$1" |
    awk -F, '{print $4, $3, $1, $2}'
}

# 12 frames of the moving light, as PNGs and as a video in one run.
mkdir -p "$work/f" "$work/d"
"$vplgi" render --scene "$here/../../scenes/cornell-moving-light.json" --technique direct --width 96 --height 64 \
  --frames 12 --fps 24 --out "$work/f/%04d.png" --video "$work/v.mp4" --quiet > "$work/render.log"
grep -q "v.mp4 (12 frames at 24 fps)" "$work/render.log" || { cat "$work/render.log"; echo "FAIL: no summary line"; exit 1; }
read -r frames rate width height < <(probe "$work/v.mp4")
check "12 frames at 24/1, 96x64" "'$frames' == '12' and '$rate' == '24/1' and '$width' == '96' and '$height' == '64'"
duration=$(ffprobe -v error -show_entries format=duration -of csv=p=0 "$work/v.mp4")
check "duration 12/24 s" "abs($duration - 0.5) < 1e-3"

# Frame i of the video against the PNGs of all 12 frames: H.264 at CRF 18 with 4:2:0 chroma leaves a
# mean error of 2.4-3.1/255 on these small frames (measured), and each frame is nearest its own PNG
# (the next nearest, a neighbour, is 0.3-1.6/255 further: the light moves every frame).
ffmpeg -v error -i "$work/v.mp4" -pix_fmt rgba "$work/d/%04d.png"
python3 - "$work" "$here" <<'PY'
import sys
work, here = sys.argv[1], sys.argv[2]
src = open(here + "/png_stats.py").read()
exec(src[:src.index("def main")])
def mad(a, b):
    wa, ha, ra = load(a); wb, hb, rb = load(b)
    assert (wa, ha) == (wb, hb)
    total = sum(abs(x - y) for row_a, row_b in zip(ra, rb) for x, y in zip(row_a, row_b))
    return total / (wa * ha * 3)
worst_same, nearest = 0.0, []
for i in range(12):
    d = [mad(f"{work}/d/{i + 1:04d}.png", f"{work}/f/{j:04d}.png") for j in range(12)]
    worst_same = max(worst_same, d[i])
    nearest.append(min(range(12), key=lambda j: d[j]))
print(f"video frame vs its PNG: worst mean |diff| {worst_same:.2f}/255; nearest PNG of each frame: {nearest}")
# 6/255: 2x the measured codec error; the order: frame i's nearest PNG is frame i's.
if not (worst_same < 6.0 and nearest == list(range(12))):
    print("FAIL: the video's frames are not the rendered frames in order"); sys.exit(1)
print("ok: video frame i is rendered frame i")
PY

# Odd sizes are padded; .mkv; with --video and no --out, no image is written.
(cd "$work" && "$vplgi" render --scene cornell --technique direct --width 33 --height 21 --frames 3 \
   --video odd.mkv --quiet > /dev/null)
read -r frames rate width height < <(probe "$work/odd.mkv")
check "odd size padded to even, mkv" "'$frames' == '3' and '$width' == '34' and '$height' == '22'"
[ ! -e "$work/out/render.png" ] || { echo "FAIL: --video alone also wrote out/render.png"; exit 1; }
echo "ok: --video alone writes no image"

# Bad input: one line, exit 1, nothing left behind.
bad() { # bad "expected message part" args...
  local expected="$1"; shift
  if "$@" > "$work/bad.log" 2>&1; then echo "FAIL: accepted: $*"; exit 1; fi
  [ "$(wc -l < "$work/bad.log")" -eq 1 ] || { echo "FAIL: more than one line: $*"; cat "$work/bad.log"; exit 1; }
  grep -q -- "$expected" "$work/bad.log" || { echo "FAIL: $* said:"; cat "$work/bad.log"; exit 1; }
  echo "ok: $expected"
}
small=(render --scene cornell --technique direct --width 32 --height 32 --quiet)
bad "a video must end in .mp4 or .mkv" "$vplgi" "${small[@]}" --video "$work/v.avi"
bad "does not exist" "$vplgi" "${small[@]}" --video "$work/nodir/v.mp4"
bad "ffmpeg is not installed" env PATH=/nonexistent "$vplgi" "${small[@]}" --video "$work/n.mp4"
# Stand-in ffmpeg programs for the two failures a real one cannot be made to show here.
mkdir -p "$work/noenc" "$work/fails"
printf '#!/bin/sh\necho " V..... mpeg4  MPEG-4 part 2"\n' > "$work/noenc/ffmpeg"
printf '#!/bin/sh\ncase "$*" in *-encoders*) echo " V....D libx264  H.264"; exit 0;; esac\necho "Unknown encoder xyz" >&2\nexit 1\n' > "$work/fails/ffmpeg"
chmod +x "$work/noenc/ffmpeg" "$work/fails/ffmpeg"
bad "has no libx264 encoder" env PATH="$work/noenc:$PATH" "$vplgi" "${small[@]}" --video "$work/n.mp4"
bad "ffmpeg .*: Unknown encoder xyz" env PATH="$work/fails:$PATH" "$vplgi" "${small[@]}" --frames 3 --video "$work/n.mp4"
left=$(ls "$work" | grep -c -E '^(n\.mp4|v\.avi)' || true)
check "no file or partial file left by the failures" "$left == 0"

# The viewer: video start at frame 1, stop at frame 6: 5 frames shown, 5 video frames at --fps 10.
command -v xvfb-run >/dev/null || { echo "FAIL: xvfb-run is not installed (run ./scripts/deps)"; exit 1; }
printf 'at 1 video start %s\nat 6 video stop\nat 7 quit\n' "$work/view.mp4" > "$work/script.txt"
xvfb-run -a -s "-screen 0 640x480x24" "$vplgi" view --scene cornell --technique direct --width 96 --height 64 \
  --fps 10 --script "$work/script.txt" > "$work/view.log" 2>&1 || { cat "$work/view.log"; exit 1; }
read -r frames rate width height < <(probe "$work/view.mp4")
check "viewer video: 5 frames at 10/1, the window's size" "'$frames' == '5' and '$rate' == '10/1' and '$width' == '96' and '$height' == '64'"
