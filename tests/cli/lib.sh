# Shared by the CLI test scripts that source it: a scratch directory ($work, kept with KEEP=1) and
# check "what" python-expression (prints ok/FAIL with the expression; FAIL exits 1).
check() {
  python3 -c "import sys; sys.exit(0 if ($2) else 1)" || { echo "FAIL: $1 ($2)"; exit 1; }
  echo "ok: $1 ($2)"
}
work=$(mktemp -d); [ -z "${KEEP:-}" ] || echo "work: $work"
trap '[ -n "${KEEP:-}" ] || rm -rf "$work"' EXIT
