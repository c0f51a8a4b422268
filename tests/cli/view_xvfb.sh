#!/usr/bin/env bash
# The viewer under Xvfb: a window opens, F12 (sent as a real key event with xdotool) writes a
# screenshot, Esc closes the window and the process exits 0.
set -eu
vplgi="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for tool in xvfb-run xdotool; do
  command -v "$tool" >/dev/null || { echo "FAIL: $tool is not installed (run ./scripts/deps)"; exit 1; }
done
cat > "$work/drive.sh" <<DRIVE
set -eu
"$vplgi" view --scene cornell --width 160 --height 120 --screenshot-dir "$work/shots" > "$work/view.log" 2>&1 &
pid=\$!
win=""
for i in \$(seq 1 300); do
  win=\$(xdotool search --name "^vplgi" 2>/dev/null | head -1 || true)
  [ -n "\$win" ] && break
  kill -0 \$pid 2>/dev/null || { cat "$work/view.log"; exit 1; }
  sleep 0.1
done
[ -n "\$win" ] || { echo "no window"; kill \$pid; exit 1; }
sleep 1
xdotool key --window "\$win" F12
for i in \$(seq 1 300); do
  ls "$work"/shots/*.png >/dev/null 2>&1 && break
  sleep 0.1
done
xdotool key --window "\$win" Escape
for i in \$(seq 1 100); do kill -0 \$pid 2>/dev/null || break; sleep 0.1; done
if kill -0 \$pid 2>/dev/null; then echo "viewer did not quit on Esc"; kill \$pid; exit 1; fi
wait \$pid
DRIVE
xvfb-run -a -s "-screen 0 640x480x24" bash "$work/drive.sh"
cat "$work/view.log"
ls -l "$work"/shots/*.png
# The screenshot is the rendered scene: the window's size, and, right of the panel (x >= 110 at this
# size), the same pixels as a headless render of the same scene (`direct`: deterministic; measured
# difference 0 of 255), which must not be black.
shot=$(ls "$work"/shots/*.png | head -1)
here=$(cd "$(dirname "$0")" && pwd)
size=$(python3 "$here/png_stats.py" size "$shot")
[ "$size" = "160 120" ] || { echo "FAIL: screenshot is $size, the window 160 120"; exit 1; }
"$vplgi" render --scene cornell --width 160 --height 120 --out "$work/headless.png" --quiet
diff=$(python3 "$here/png_stats.py" diff "$shot" "$work/headless.png" 110 0 160 120)
mean=$(python3 "$here/png_stats.py" mean "$work/headless.png" 110 0 160 120)
echo "right of the panel: mean |screenshot - headless render| $diff, headless mean $mean (8-bit display values)"
python3 -c "import sys; sys.exit(0 if $diff < 0.5 and $mean > 5 else 1)" \
  || { echo "FAIL: the screenshot is not the rendered scene"; exit 1; }
echo "viewer checks passed"
