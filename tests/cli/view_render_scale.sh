#!/usr/bin/env bash
# The viewer's internal resolution (issue 28 part 5, app/render_scale.h) under Xvfb, read from
# `view --stats` (frame, ms, internal size per frame):
#   - a fixed viewer.renderScale renders at that fraction of the window, never below 320 x 180;
#   - the automatic scale on llvmpipe starts at the floor, stays there under an unreachable target
#     and grows to the window's size under a generous one;
#   - a script's `set viewer.renderScale=...` changes it between frames; screenshots stay window-sized;
#   - a bad value or an unknown viewer key is one error line before a window opens.
set -eu
vplgi="$(realpath "$1")"
here="$(cd "$(dirname "$0")" && pwd)"
. "$here/lib.sh" # check, $work
command -v xvfb-run >/dev/null || { echo "FAIL: xvfb-run is not installed (run ./scripts/deps)"; exit 1; }
view() { # view NAME FRAMES [args...]: runs the viewer for FRAMES frames, stats in $work/NAME.csv
  local name="$1" frames="$2"; shift 2
  [ -e "$work/$name.txt" ] || printf 'at %d quit\n' "$frames" > "$work/$name.txt"
  xvfb-run -a -s "-screen 0 1024x768x24" "$vplgi" view --scene cornell --technique direct --no-panel \
    --script "$work/$name.txt" --stats "$work/$name.csv" "$@" > "$work/$name.log" 2>&1 || { cat "$work/$name.log"; exit 1; }
}
sizes() { # sizes NAME: "w x h" of each frame, one per line
  tail -n +2 "$work/$1.csv" | awk -F, '{print $3 "x" $4}'
}

view fixed 3 --width 960 --height 540 --set viewer.renderScale=0.5
check "scale 0.5 of 960x540" "'$(sizes fixed | sort -u)' == '480x270'"
view floor 3 --width 960 --height 540 --set viewer.renderScale=0.05
check "scale 0.05 stops at 320x180" "'$(sizes floor | sort -u)' == '320x180'"
view script-default 3 --width 480 --height 320
check "under --script the default is 1" "'$(sizes script-default | sort -u)' == '480x320'"

view unreachable 8 --width 960 --height 540 --set viewer.renderScale=auto --set viewer.targetMs=1
check "auto under an unreachable target: the floor" "'$(sizes unreachable | sort -u)' == '320x180'"
view generous 16 --width 640 --height 360 --set viewer.renderScale=auto --set viewer.targetMs=60000
first=$(sizes generous | head -1); last=$(sizes generous | tail -1)
check "auto under a generous target grows from the floor to the window" "'$first' == '320x180' and '$last' == '640x360'"

# A script changes the scale between frames; a screenshot is the window's size.
printf 'at 2 set viewer.renderScale=0.75\nat 4 screenshot %s\nat 5 quit\n' "$work/shot.png" > "$work/scripted.txt"
view scripted 5 --width 640 --height 360
check "set viewer.renderScale in a script" "'$(sizes scripted | tr '\n' ' ')' == '640x360 640x360 480x270 480x270 480x270 480x270 '"
check "the screenshot is window-sized" "'$(python3 "$here/png_stats.py" size "$work/shot.png")' == '640 360'"

# Bad input: one line, exit 1, no window.
bad() { # bad "expected" args...
  local expected="$1"; shift
  if "$vplgi" view --scene cornell "$@" > "$work/bad.log" 2>&1; then echo "FAIL: accepted: $*"; exit 1; fi
  [ "$(wc -l < "$work/bad.log")" -eq 1 ] || { echo "FAIL: more than one line: $*"; cat "$work/bad.log"; exit 1; }
  grep -q -- "$expected" "$work/bad.log" || { echo "FAIL: $* said:"; cat "$work/bad.log"; exit 1; }
  echo "ok: $expected"
}
bad 'viewer.renderScale: "2" is not a number in' --set viewer.renderScale=2
bad 'viewer.targetMs: "fast" is not a number in' --set viewer.targetMs=fast
bad 'unknown parameter "viewer.nosuch"' --set viewer.nosuch=1
