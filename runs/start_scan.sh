#!/usr/bin/env bash
# start_scan.sh PROG SCENE DIR X0:DX:COUNT [--set KEY=VALUE ...]
# start_scan.sh PROG SCENE DIR @FILE [--set KEY=VALUE ...]
#
# A start scan of the four-ball coupled scenes (runs/coupled_fig8.ini,
# runs/coupled_fig9.ini): runs with the outer balls at -X and +X (ball 1
# at -X, ball 4 at +X; the inner balls as in SCENE), X = X0 + k DX for
# k = 0 .. COUNT-1, or the X listed in FILE (one a line).  `ballfilm sweep` varies its axes independently, and a
# symmetric start needs two keys tied together, hence this driver.
# Each run writes DIR/x_X.h5 (X with four decimals); a run whose file
# exists is skipped, so a rerun continues an interrupted scan (the program
# writes under a temporary name and renames at the end).  The extra
# arguments are passed to every run.  JOBS (default 2) runs in parallel,
# each under nice.  plots/fig9_scan.py summarises a scan directory.
set -eu
if [ $# -lt 4 ]; then
    echo "usage: $0 PROG SCENE DIR X0:DX:COUNT|@FILE [--set KEY=VALUE ...]" >&2
    exit 2
fi
PROG=$1 SCENE=$2 DIR=$3 XS=$4
shift 4
mkdir -p "$DIR"
export PROG SCENE DIR
run_case() {
    local x=$1 out
    shift
    out="$DIR/x_$x.h5"
    [ -e "$out" ] && return 0
    nice -n 10 "$PROG" run "$SCENE" -q -o "$out" \
        --set "ball.1.position=-$x" --set "ball.4.position=$x" "$@" \
        > "$DIR/x_$x.log" 2>&1 || echo "X = $x: exit $? (see $DIR/x_$x.log)" >&2
}
export -f run_case
case "$XS" in
@*) xlist() { awk 'NF { printf "%.4f\n", $1 }' "${XS#@}"; } ;;
*) IFS=: read -r X0 DX COUNT <<< "$XS"
   xlist() { awk -v a="$X0" -v d="$DX" -v n="$COUNT" \
       'BEGIN { for (k = 0; k < n; k++) printf "%.4f\n", a + k * d }'; } ;;
esac
xlist | xargs -P "${JOBS:-2}" -I{} bash -c 'run_case "$@"' _ {} "$@"
