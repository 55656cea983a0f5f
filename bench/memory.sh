#!/usr/bin/env bash
# bench/memory.sh: peak resident memory of the shipped two-ball scene
# (runs/two_balls_B.ini: MV2M, energy every step, the return map, output
# every 100 steps) at t_end = 10 s and 10^4 s (10^5 and 10^8 steps); the
# goal (issue 21) is the same peak within 2 MiB, whatever the length of the
# run.  The peak is the program's own (VmHWM, its summary line).  Run by
# make bench; the long run takes about ten seconds.
set -euo pipefail
cd "$(dirname "$0")/.."
tmp=$(mktemp -d /tmp/ballfilm-bench-memory.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
peak() {
    bin/ballfilm run runs/two_balls_B.ini -q -o "$tmp/m.h5" \
        --set scene.t_end="$1" | awk '/^peak memory:/ {print $3}'
}
a=$(peak 10)
b=$(peak 1e4)
printf 'peak memory of runs/two_balls_B.ini\n'
printf '  t_end = 10 s:     %6.1f MiB\n' "$a"
printf '  t_end = 10^4 s:   %6.1f MiB   difference %.1f MiB (goal < 2)\n' \
    "$b" "$(awk -v a="$a" -v b="$b" 'BEGIN{print b - a}')"
