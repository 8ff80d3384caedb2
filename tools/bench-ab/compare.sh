#!/usr/bin/env bash
# Two builds of zline against each other, interleaved (issue 30's trials):
# each side is a copy of target/ab/target/release/zline-bench-ab built by
# run.sh from one version of the code; the script runs them in turn, N
# times each, 11 rounds a run, and prints each pair's new_ms (today's side
# of the bench, the code each copy was built from), their ratio B/A, and
# the medians:
#   tools/bench-ab/run.sh --rounds 1 && cp target/ab/target/release/zline-bench-ab /tmp/a
#   (change the code)
#   tools/bench-ab/run.sh --rounds 1 && cp target/ab/target/release/zline-bench-ab /tmp/b
#   tools/bench-ab/compare.sh /tmp/a /tmp/b 11 [MESH.obj] [--size WxH] [--cull none|back]
# The last line is
#   medA=.. medB=.. medratio B/A=..
# with medratio below 1.00 when B's code is faster.
set -euo pipefail
if [ $# -lt 3 ]; then
  sed -n '2,15p' "$0" >&2
  exit 2
fi
a=$1
b=$2
runs=$3
shift 3
new_ms() { "$1" "${@:2}" --rounds 11 | tail -1 | sed -E 's/.*new_ms=([0-9.]+).*/\1/'; }
for _ in $(seq "$runs"); do
  echo "$(new_ms "$a" "$@") $(new_ms "$b" "$@")"
done | python3 -c '
import statistics as s, sys
rows = [tuple(map(float, line.split())) for line in sys.stdin if line.strip()]
for a, b in rows:
    print(a, b, round(b / a, 3))
print("medA=%.3f medB=%.3f medratio B/A=%.3f" % (
    s.median(a for a, _ in rows), s.median(b for _, b in rows), s.median(b / a for a, b in rows)))'
