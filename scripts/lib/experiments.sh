# Shared by scripts/*-experiments (sourced): each named run is one `vplgi compare` writing
# out/experiments/<name>/ (index.html, metrics.csv, metrics.json), with its summary printed.
# The caller sets `selected` (the names asked for; empty: all but the optional ones) and
# `optional_suffixes` (names ending so run only when named), then calls `want NAME && run NAME ARGS`.
vplgi=${VPLGI:-build/app/vplgi}
out=out/experiments
mkdir -p "$out"
run() { # name, then compare arguments
  local name=$1
  shift
  if [ "$#" -eq 0 ]; then return; fi
  echo "== $name: vplgi compare $*"
  local start=$SECONDS
  "$vplgi" compare --out "$out/$name" "$@" 2>"$out/$name.log" | grep -v "index.html" || { cat "$out/$name.log"; exit 1; }
  echo "   (metrics: $out/$name/metrics.csv; $((SECONDS - start)) s)"
  cut -d, -f1-9 "$out/$name/metrics.csv" | sed 's/^/   /'
}
want() {
  if [ "${#selected[@]}" -gt 0 ]; then [[ " ${selected[*]} " == *" $1 "* ]]; return; fi
  local suffix
  for suffix in "${optional_suffixes[@]}"; do [[ "$1" == *"$suffix" ]] && return 1; done
  return 0
}
