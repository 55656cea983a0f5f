#!/usr/bin/env bash
# bench/support_ab.sh REV|FILE [n] [pairs]: the support-set gravity's fast
# method of this tree against src/particles/support_fast.c as it was at
# REV (a commit, tag or branch; or the path of a file, such as a copy of
# support_fast.c kept before a change), both compiled into one program
# (bench/driver/g72_support_ab.c) and run alternately in one process on
# the Greenspan 1972 benchmark scene at N = n^2 (default n = 256), `pairs`
# pairs of evaluations (default 30).  Prints both times, the median of the
# pairs' ratios (REV / this tree) and whether g and the kinds are the same
# bits (exit 1 if not).  For work on src/particles/support_fast.c: REV's
# file must use the same workspace (support_impl.h) as this tree's, and
# both use this tree's empty bands (support_gaps.c; a file from before
# 60ec7b8, which split them off, defines the searches that support_impl.h
# now holds and does not compile here).
# Builds build/libballfilm.a first.
set -euo pipefail
if [ $# -lt 1 ]; then
    echo "usage: bench/support_ab.sh REV|FILE [n] [pairs]" >&2
    exit 2
fi
REV=$1
# a file is named from where the script was called
if [ -f "$REV" ]; then REV=$(realpath "$REV"); fi
cd "$(dirname "$0")/.."
N=${2:-256}
PAIRS=${3:-30}
tmp=$(mktemp -d /tmp/ballfilm-support-ab.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
if [ -f "$REV" ]; then
    cp "$REV" "$tmp/other.c"
else
    git show "$REV:src/particles/support_fast.c" > "$tmp/other.c"
fi
. bench/driver/build.sh
driver_library "$tmp/build.log"
# shellcheck disable=SC2086
gcc $DRIVER_CFLAGS -fopenmp -Iinclude -Isrc $DRIVER_INC \
    -Dbf_sup_eval_fast=bf_sup_eval_fast_other -c "$tmp/other.c" \
    -o "$tmp/other.o"
# shellcheck disable=SC2086
gcc $DRIVER_CFLAGS -fopenmp -Iinclude -Isrc -Ibench/driver $DRIVER_INC \
    bench/driver/g72_support_ab.c "$tmp/other.o" build/libballfilm.a \
    $DRIVER_LIBS -o "$tmp/g72_support_ab"
echo "support-set gravity, this tree against support_fast.c of $REV:"
"$tmp/g72_support_ab" "$N" "$PAIRS"
