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
python3 -c "import sys; d=open(sys.argv[1],'rb').read(); sys.exit(0 if d[:8]==b'\x89PNG\r\n\x1a\n' and len(d) > 200 else 1)" "$(ls "$work"/shots/*.png | head -1)"
echo "viewer checks passed"
