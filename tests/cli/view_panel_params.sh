#!/usr/bin/env bash
# The viewer's panel lists exactly the parameters `vplgi render --list-params` lists, for every
# technique (`vplgi scenes` names them, so a new technique is covered without editing this test):
# both come from the one visitParams field list, and neither may grow a list of its own.
set -eu
vplgi="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
command -v xvfb-run >/dev/null || { echo "FAIL: xvfb-run is not installed (run ./scripts/deps)"; exit 1; }
techniques=$("$vplgi" scenes | sed -n 's/^techniques: //p')
[ -n "$techniques" ] || { echo "FAIL: vplgi scenes lists no techniques"; exit 1; }

# --technique all prints each technique's block: "technique = T" then "key = value  # doc ...".
"$vplgi" render --list-params --technique all > "$work/all.txt"
for t in $techniques; do
  grep -qx "technique = $t" "$work/all.txt" || { echo "FAIL: --technique all has no block for $t"; exit 1; }
done

here=$(cd "$(dirname "$0")" && pwd)
cat > "$work/dump.sh" <<DUMP
set -eu
. "$here/small_budgets.sh"
for t in $techniques; do
  # Small window and budgets (values do not change the keys): the panel's keys come after the
  # first frame, whatever it costs on llvmpipe.
  small_budgets "\$t"
  "$vplgi" view --scene cornell --technique "\$t" --width 96 --height 64 "\${small[@]}" \
    --dump-panel-params "$work/panel-\$t.txt" > "$work/view-\$t.log" 2>&1 || { cat "$work/view-\$t.log"; exit 1; }
done
DUMP
xvfb-run -a -s "-screen 0 640x480x24" bash "$work/dump.sh"

for t in $techniques; do
  "$vplgi" render --list-params --technique "$t" | sed -n 's/^\([^ ]*\) = .*/\1/p' | grep -vx technique | sort > "$work/list-$t.txt"
  sort "$work/panel-$t.txt" > "$work/panel-$t.sorted"
  n=$(wc -l < "$work/list-$t.txt")
  [ "$n" -gt 5 ] || { echo "FAIL: $t lists only $n parameters"; exit 1; }
  if ! diff "$work/panel-$t.sorted" "$work/list-$t.txt" > "$work/diff-$t.txt"; then
    echo "FAIL: $t: the panel's keys (<) and render --list-params (>) differ:"; cat "$work/diff-$t.txt"; exit 1
  fi
  # Each key once: a duplicate in the panel would be a second widget for one field.
  [ "$(sort -u "$work/panel-$t.txt" | wc -l)" -eq "$(wc -l < "$work/panel-$t.txt")" ] || { echo "FAIL: $t: a key twice in the panel"; exit 1; }
  echo "ok: $t: the panel and render --list-params list the same $n keys"
done
echo "panel parameter checks passed"
