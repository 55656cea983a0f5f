#!/usr/bin/env bash
# bench/g72_ranks.sh: Greenspan 1972 split over MPI ranks
# (src/models/g72_ranks.c).  (1) 100 steps of runs/greenspan72_large.ini
# (200704 particles) on 1 and on 2 ranks, alternately, PAIRS times (default
# 3): the wall times of the loop (the program's "wall time", set-up not
# counted) and of the whole process, the median of the per-pair ratios
# 2 ranks / 1 rank, and whether the files are the same bit for bit.  (2)
# 10^6 particles (the same physics in a box 6250 cm wide) for 5 steps on 1,
# 2 and 4 ranks: each rank's peak resident memory (/usr/bin/time %M).  (3)
# A scene of 3162^2 = 9998244 particles (a box 19762.5 cm wide) for STEPS
# and 2 STEPS steps (default 3) on 1 and on 2 ranks: the time of a step
# (the difference of the loops' wall times over STEPS), the rest of the
# loop (its two output rows, which over ranks rank 0 gathers), and each
# rank's peak memory.  Run by make bench; G72_RANKS_BIG=0 skips (3), which
# needs about 4 GB and 3 minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
PAIRS=${PAIRS:-3}
STEPS=${STEPS:-3}
tmp=$(mktemp -d /tmp/ballfilm-bench-g72ranks.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
scene=runs/greenspan72_large.ini
# run R OUT [ARGS...]: prints "loop-seconds process-seconds"; stdout kept
run() {
    local R=$1 out=$2 s e
    shift 2
    s=$(date +%s.%N)
    mpirun -n "$R" --oversubscribe bin/ballfilm-mpi run "$@" -o "$out" -q \
        > "$out.log"
    e=$(date +%s.%N)
    awk -v a="$s" -v b="$e" '/^wall time:/ { w = $3 }
        END { printf "%s %.3f\n", w, b - a }' "$out.log"
}
ratios=() prow=()
same=yes
for ((k = 0; k < PAIRS; k++)); do
    read -r l1 p1 < <(run 1 "$tmp/r1.h5" "$scene" --set scene.t_end=1)
    read -r l2 p2 < <(run 2 "$tmp/r2.h5" "$scene" --set scene.t_end=1)
    ratios+=("$(awk -v a="$l2" -v b="$l1" 'BEGIN { printf "%.3f", a / b }')")
    prow+=("$(awk -v a="$p2" -v b="$p1" 'BEGIN { printf "%.3f", a / b }')")
    printf '  pair %d: loop 1 rank %.2f s, 2 ranks %.2f s; process %.2f s, %.2f s\n' \
        "$k" "$l1" "$l2" "$p1" "$p2"
    /usr/bin/python3 tests/compare/h5same.py "$tmp/r1.h5" "$tmp/r2.h5" \
        > /dev/null || same=no
done
median() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 }
    END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
printf 'greenspan72, 200704 particles, 100 steps, 2 MPI ranks / 1 rank\n'
printf '  loop wall time: median %s (pairs %s)\n' "$(median "${ratios[@]}")" \
    "${ratios[*]}"
printf '  whole process:  median %s (pairs %s)\n' "$(median "${prow[@]}")" \
    "${prow[*]}"
printf '  files the same on 1 and 2 ranks: %s\n' "$same"
printf '  load average: %s\n' "$(cut -d' ' -f1-3 /proc/loadavg)"
# peaks R OUT ARGS...: each rank's peak resident memory in MiB, rank
# order not kept (sorted), then the loop's wall time
peaks() {
    local R=$1 out=$2
    shift 2
    mpirun -n "$R" --oversubscribe bash -c \
        '/usr/bin/time -f "peak %M" -o "$0.$OMPI_COMM_WORLD_RANK" \
         bin/ballfilm-mpi run "$@"' "$out" "$@" -o "$out" -q > "$out.log"
    awk '/^peak/ { printf "%.0f ", $2 / 1024 }' "$out".[0-9]* | tr ' ' '\n' |
        sort -n | tr '\n' ' '
}
mid=(--set greenspan72.width=6250 --set greenspan72.height=6250
     --set greenspan72.interface=4687.5 --set greenspan72.grid_nx=1000
     --set greenspan72.grid_ny=1000 --set greenspan72.output=diagnostics
     --set scene.t_end=0.05)
printf 'greenspan72, 10^6 particles, 5 steps: peak resident memory of each rank, MiB\n'
for R in 1 2 4; do
    printf '  %d rank(s): %s\n' "$R" "$(peaks "$R" "$tmp/mid$R.h5" "$scene" "${mid[@]}")"
done
if [ "${G72_RANKS_BIG:-1}" != 0 ]; then
    big=(--set greenspan72.width=19762.5 --set greenspan72.height=19762.5
         --set greenspan72.interface=14821.875 --set greenspan72.grid_nx=3162
         --set greenspan72.grid_ny=3162 --set greenspan72.output=diagnostics
         --set scene.output_every=1000000)
    # loop LOG: the loop's wall time of a run
    loop() { awk '/^wall time:/ { print $3 }' "$1"; }
    printf 'greenspan72, 9998244 particles: a step from runs of %s and %s steps (each with 2 output rows)\n' \
        "$STEPS" "$((2 * STEPS))"
    for R in 1 2; do
        mem=$(peaks "$R" "$tmp/big$R.h5" "$scene" "${big[@]}" \
              --set "scene.t_end=$(awk -v n="$STEPS" 'BEGIN { print n / 100 }')")
        peaks "$R" "$tmp/big2x$R.h5" "$scene" "${big[@]}" \
            --set "scene.t_end=$(awk -v n="$STEPS" 'BEGIN { print 2 * n / 100 }')" > /dev/null
        a=$(loop "$tmp/big$R.h5.log") b=$(loop "$tmp/big2x$R.h5.log")
        printf '  %d rank(s): %.2f s a step, %.2f s the rest of the loop (the rows); peak memory of each rank %s MiB\n' \
            "$R" "$(awk -v a="$a" -v b="$b" -v n="$STEPS" 'BEGIN { print (b - a) / n }')" \
            "$(awk -v a="$a" -v b="$b" -v n="$STEPS" 'BEGIN { print 2 * a - b }')" "$mem"
    done
    /usr/bin/python3 tests/compare/h5same.py "$tmp/big2x1.h5" "$tmp/big2x2.h5" \
        > /dev/null && printf '  files the same: yes\n' || printf '  files the same: no\n'
fi
