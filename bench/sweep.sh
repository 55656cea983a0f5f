#!/usr/bin/env bash
# bench/sweep.sh: a 16-case sweep (two falling balls, lower mass 0.5..2 g,
# 300 s each) on 1 and on 2 MPI ranks, and on a pool of 2 processes; prints
# the wall times and speed-ups measured in this one run.  Run by make bench.
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
tmp=$(mktemp -d /tmp/ballfilm-bench-sweep.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
args=(sweep runs/two_balls_B.ini --vary ball.1.mass=0.5:2.0:16
      --set scene.t_end=300 --set scene.output_every=1000 -q)
t() { local s e; s=$(date +%s.%N); "$@" >/dev/null; e=$(date +%s.%N); awk -v a="$s" -v b="$e" 'BEGIN{print b - a}'; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN{printf "%.2f", a / b}'; }
t1=$(t mpirun -n 1 bin/ballfilm-mpi "${args[@]}" -o "$tmp/r1")
t2=$(t mpirun -n 2 --oversubscribe bin/ballfilm-mpi "${args[@]}" -o "$tmp/r2")
tp=$(t bin/ballfilm "${args[@]}" -o "$tmp/p2" --jobs 2)
# the same datasets bit for bit and the same root attributes, except what
# describes the run itself (its random run_id, the version, wall times:
# tests/compare/h5same.py); h5diff would count the run_id
same=yes
for f in "$tmp"/r1/case_*.h5; do
    /usr/bin/python3 tests/compare/h5same.py "$f" \
        "$tmp/r2/$(basename "$f")" >/dev/null || same=no
done
printf 'sweep of 16 cases (300 s of two falling balls each)\n'
printf '  1 MPI rank:        %6.2f s\n' "$t1"
printf '  2 MPI ranks:       %6.2f s   speed-up %s\n' "$t2" "$(ratio "$t1" "$t2")"
printf '  2-process pool:    %6.2f s   speed-up %s\n' "$tp" "$(ratio "$t1" "$tp")"
printf '  per-case files identical between 1 and 2 ranks: %s\n' "$same"
