#!/usr/bin/env bash
# Side-by-side timing of two tandem binaries (e.g. main before and after a change), interleaved
# round by round so machine drift hits both alike. Prints the median frame ms of each benchmark
# per binary and their ratio (new / old).
#   scripts/bench-compare.sh OLD_TANDEM NEW_TANDEM [ROUNDS]
set -euo pipefail
old=$1 new=$2 rounds=${3:-3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
benches=(
  "atrium --pipeline deferred"
  "atrium --pipeline deferred-rt-gbuffer"
  "spheres --pipeline hybrid-heuristic"
  "spheres --pipeline hybrid-all"
  "spheres --pipeline rt-only"
)
frame() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['total']['median_ms'])" "$1"; }
printf '%-42s %10s %10s %7s\n' benchmark old_ms new_ms ratio
for b in "${benches[@]}"; do
  o=() n=()
  for r in $(seq "$rounds"); do
    # shellcheck disable=SC2086
    "$old" bench $b --frames 20 --warmup 3 --json "$tmp/o.json" >/dev/null
    o+=("$(frame "$tmp/o.json")")
    # shellcheck disable=SC2086
    "$new" bench $b --frames 20 --warmup 3 --json "$tmp/n.json" >/dev/null
    n+=("$(frame "$tmp/n.json")")
  done
  python3 - "$b" "${o[*]}" "${n[*]}" <<'PY'
import statistics, sys
name, o, n = sys.argv[1], [float(x) for x in sys.argv[2].split()], [float(x) for x in sys.argv[3].split()]
mo, mn = statistics.median(o), statistics.median(n)
print(f"{name:<42} {mo:10.1f} {mn:10.1f} {mn / mo:7.3f}")
PY
done
