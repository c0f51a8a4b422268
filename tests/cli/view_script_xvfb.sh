#!/usr/bin/env bash
# The viewer driven by a frame-timed --script under Xvfb (issue 12's acceptance): a parameter change,
# a debug view, a picture-in-picture, a technique switch, the help overlay, a recorded camera path and
# screenshots, checked by their pixels:
#   - the panel is drawn: its region differs between a screenshot with and one without the panel,
#     while the rest of the window is the same image;
#   - the scene is lit (non-black mean), the debug view differs from the final image, a higher
#     renderer.exposure gives a brighter mean, the technique switch adds indirect light;
#   - the recorded path is a scene file whose animation `vplgi render --frames N --out pattern` plays;
#   - bad script lines and failing commands are one-line errors with a non-zero exit.
set -eu
vplgi="$1"
here="$(cd "$(dirname "$0")" && pwd)"
stats() { python3 "$here/png_stats.py" "$@"; }
. "$here/lib.sh" # check, $work
command -v xvfb-run >/dev/null || { echo "FAIL: xvfb-run is not installed (run ./scripts/deps)"; exit 1; }

# Bad scripts fail before a window opens: one line naming FILE:LINE, exit status 1.
bad() { # bad "script text" "expected message part"
  printf '%s\n' "$1" > "$work/bad.txt"
  if "$vplgi" view --scene cornell --script "$work/bad.txt" > "$work/bad.log" 2>&1; then
    echo "FAIL: script \"$1\" was accepted"; exit 1
  fi
  [ "$(wc -l < "$work/bad.log")" -eq 1 ] || { echo "FAIL: more than one line for \"$1\""; cat "$work/bad.log"; exit 1; }
  grep -q "bad.txt:1: .*$2" "$work/bad.log" || { echo "FAIL: \"$1\" said:"; cat "$work/bad.log"; exit 1; }
}
bad "at x quit" "is not a frame number"
bad "jump 3" "unknown command"
bad "technique nosuch" "unknown technique"
bad "set exposure" "is not KEY=VALUE"
bad "screenshot a.jpg" "must end in .png"
bad "key F13" "unknown key"
bad "panel maybe" "usage: panel on|off"
bad "camera 1 2 3" "usage: camera"
bad "video start v.avi" "must end in .mp4 or .mkv"
bad "video" "usage: video start"
echo "ok: bad script lines are one-line errors"

# A failing command while running: the error names the line, the exit status is non-zero.
printf 'at 1 set renderer.nosuch=1\nat 2 quit\n' > "$work/fail.txt"
if xvfb-run -a -s "-screen 0 640x480x24" "$vplgi" view --scene cornell --technique direct --width 96 --height 64 \
     --script "$work/fail.txt" > "$work/fail.log" 2>&1; then
  echo "FAIL: an unknown parameter in a script did not fail"; exit 1
fi
grep -q "fail.txt:1: set: unknown parameter \"renderer.nosuch\"" "$work/fail.log" || { cat "$work/fail.log"; exit 1; }
echo "ok: a failing script command stops the viewer with its line"

# Commands at frame N act before frame N is drawn; its screenshots show frame N. A window that
# appears (the F1 overlay) is drawn from the frame after (Dear ImGui sizes it first).
# 480 x 320: the panel is min(360, 480 / 2) = 240 pixels wide, at the left.
s="$work/shots"
mkdir -p "$s"
cat > "$work/script.txt" <<SCRIPT
at 2 screenshot $s/panel.png
at 3 screenshot-panel off
     screenshot $s/final.png
at 4 set renderer.exposure=4
     screenshot $s/bright.png
at 5 display normal
     screenshot $s/normal.png
at 6 display final
     pip normal
     screenshot $s/pip.png
at 7 pip off
     dump-params $work/panel-direct.txt
     technique ir
     set ir.vplCount=64 ir.shadowMapSize=32 ir.fixedSequence=true
at 9 screenshot $s/ir.png
at 10 screenshot-panel on
      key F1
at 11 screenshot $s/help.png
at 12 key F1
      camera -0.278 0.273 0.8 -0.278 0.273 0.0
      record start
at 13 camera -0.2 0.3 0.7 -0.278 0.273 0.0
at 14 camera -0.1 0.35 0.6 -0.278 0.273 0.0
at 15 record stop $work/path.json
      quit
SCRIPT
xvfb-run -a -s "-screen 0 640x480x24" "$vplgi" view --scene cornell --technique direct --width 480 --height 320 \
  --script "$work/script.txt" > "$work/view.log" 2>&1 || { cat "$work/view.log"; exit 1; }
grep -q "^technique = ir" "$work/view.log"
for f in panel final bright normal pip ir help; do test -s "$s/$f.png"; done
test -s "$s/final.exr" # the linear frame beside each screenshot

panel_diff=$(stats diff "$s/panel.png" "$s/final.png" 0 0 240 320)
scene_diff=$(stats diff "$s/panel.png" "$s/final.png" 250 0 480 320)
check "the panel is drawn (its region differs with and without it)" "$panel_diff > 10"
# Frame-to-frame the direct technique is deterministic: the diffs below measured 0.000 when the
# images should agree, 15-90 where they should differ.
check "outside the panel the two screenshots show the same frame" "$scene_diff < 0.5"
final_mean=$(stats mean "$s/final.png")
bright_mean=$(stats mean "$s/bright.png")
check "the scene is lit" "$final_mean > 8"
check "renderer.exposure=4 brightens the image" "$bright_mean > $final_mean + 5"
normal_diff=$(stats diff "$s/normal.png" "$s/bright.png")
check "the normal debug view differs from the final image" "$normal_diff > 10"
pip_corner=$(stats diff "$s/pip.png" "$s/bright.png" -128 -88 -8 -8)
pip_rest=$(stats diff "$s/pip.png" "$s/bright.png" 0 0 300 200)
check "the picture-in-picture is drawn in the bottom right corner" "$pip_corner > 10"
check "the rest of the window is the final image" "$pip_rest < 0.5"
ir_mean=$(stats mean "$s/ir.png")
check "switching to ir (exposure carried over) adds indirect light" "$ir_mean > $bright_mean + 2"
# ir.fixedSequence: the same VPLs every frame, so frames 9 and 11 differ only by the overlay.
help_diff=$(stats diff "$s/help.png" "$s/ir.png" 250 0 480 320)
check "F1 draws the help overlay over the scene" "$help_diff > 10"

# The panel's keys are the technique's parameter list (the full comparison for every technique is
# tests/cli/view_panel_params.sh).
"$vplgi" render --list-params --technique direct | sed -n 's/^\([^ ]*\) = .*/\1/p' | grep -v '^technique$' | sort > "$work/list-direct.txt"
sort "$work/panel-direct.txt" | diff - "$work/list-direct.txt"
echo "ok: the panel's keys equal render --list-params (direct)"

# The recorded path replays: a scene file with the animation "recorded"; a frame sequence from it.
grep -q '"recorded"' "$work/path.json"
mkdir -p "$work/seq"
"$vplgi" render --scene "$work/path.json" --technique direct --frames 4 --fps 30 --width 64 --height 48 \
  --out "$work/seq/%04d.png" --quiet > "$work/seq.log"
for i in 0000 0001 0002 0003; do test -s "$work/seq/$i.png"; done
path_diff=$(stats diff "$work/seq/0000.png" "$work/seq/0003.png")
check "the replayed camera path moves the camera" "$path_diff > 1"
# ... and plays in the viewer (P / play on) at the fixed step: frames 1 and 3 of the playback
# equal render's frames 1 and 3 (the same animation time 1/fps per frame; panel hidden): measured
# 0.000, the same bytes; 0.5 allows a stray pixel or two, far below a camera step (~17).
cat > "$work/play.txt" <<SCRIPT
panel off
play on
at 1 screenshot $s/play1.png
at 3 screenshot $s/play3.png
     quit
SCRIPT
xvfb-run -a -s "-screen 0 640x480x24" "$vplgi" view --scene "$work/path.json" --technique direct --width 64 --height 48 \
  --fps 30 --script "$work/play.txt" > "$work/play.log" 2>&1 || { cat "$work/play.log"; exit 1; }
play_moves=$(stats diff "$s/play1.png" "$s/play3.png")
play_vs_render1=$(stats diff "$s/play1.png" "$work/seq/0001.png")
play_vs_render3=$(stats diff "$s/play3.png" "$work/seq/0003.png")
check "playback moves the camera" "$play_moves > 1"
check "playback frame 1 is render's frame 1" "$play_vs_render1 < 0.5"
check "playback frame 3 is render's frame 3" "$play_vs_render3 < 0.5"

# Hot shader reload: a broken shader keeps the old program (the scene still draws) and its error is
# shown in the window; the repaired one reloads. wait-file holds the viewer at a frame while this
# script edits a copy of glsl/ (VPLGI_GLSL_DIR).
cp -r "$here/../../glsl" "$work/glsl"
cp "$work/glsl/passes/tonemap.frag" "$work/tonemap.frag.orig"
cat > "$work/reload.txt" <<SCRIPT
panel off
at 1 screenshot $s/before.png
at 2 wait-file $work/broken
     reload
at 3 screenshot $s/reload-error.png
at 4 wait-file $work/fixed
     reload
at 5 screenshot $s/reload-fixed.png
     quit
SCRIPT
cat > "$work/reload.sh" <<DRIVE
set -eu
VPLGI_GLSL_DIR="$work/glsl" "$vplgi" view --scene cornell --technique direct --width 480 --height 320 \
  --script "$work/reload.txt" > "$work/reload.log" 2>&1 &
pid=\$!
wait_for() { for i in \$(seq 1 1200); do [ -e "\$1" ] && return 0; kill -0 \$pid 2>/dev/null || break; sleep 0.1; done; echo "no \$1"; cat "$work/reload.log"; exit 1; }
wait_for "$s/before.png"
echo "this is not GLSL" >> "$work/glsl/passes/tonemap.frag"
touch "$work/broken"
wait_for "$s/reload-error.png"
cp "$work/tonemap.frag.orig" "$work/glsl/passes/tonemap.frag"
touch "$work/fixed"
wait \$pid
DRIVE
xvfb-run -a -s "-screen 0 640x480x24" bash "$work/reload.sh" || { cat "$work/reload.log"; exit 1; }
grep -q "shader reload failed, keeping the old shaders: glsl/passes/tonemap.frag:" "$work/reload.log" ||
  { echo "FAIL: no reload error naming glsl/passes/tonemap.frag"; cat "$work/reload.log"; exit 1; }
grep -q "^shaders reloaded" "$work/reload.log" || { echo "FAIL: the repaired shader did not reload"; exit 1; }
# The error window spans the top centre (measured difference there 45; the scene below it 0.000).
error_top=$(stats diff "$s/reload-error.png" "$s/before.png" 100 0 380 60)
error_bottom=$(stats diff "$s/reload-error.png" "$s/before.png" 0 240 480 320)
fixed_diff=$(stats diff "$s/reload-fixed.png" "$s/before.png")
check "the shader error is shown in the window" "$error_top > 10"
check "the old programs still draw the scene" "$error_bottom < 0.5"
check "after the repair the window is the scene again" "$fixed_diff < 0.5"
echo "viewer script checks passed"
