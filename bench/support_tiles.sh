#!/usr/bin/env bash
# bench/support_tiles.sh: the support-set gravity's fast method on one
# local configuration copied side by side in x 1 to 64 times (Greenspan
# 1972 benchmark scene at n = 64, 128 and 256 after 100 steps), so that N
# grows from 4096 to 262144 with the same work per particle: does the time
# per particle grow when the arrays outgrow the caches?  (issue 21 item 5;
# docs/performance.md, "Eighth round".)  bench/driver/g72_support_tiles.c
# says what is measured.  Run by make bench (about 10 s).
# Builds build/libballfilm.a first.
set -euo pipefail
cd "$(dirname "$0")/.."
tmp=$(mktemp -d /tmp/ballfilm-support-tiles.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
make --no-print-directory -j2 build/libballfilm.a > "$tmp/build.log" 2>&1 ||
    { tail -20 "$tmp/build.log"; exit 1; }
CFLAGS="-std=c11 -O2 -Wall -Wextra -Werror -ffp-contract=off -D_POSIX_C_SOURCE=200809L"
INC="$(pkg-config --cflags hdf5-serial gsl)"
LIBS="$(pkg-config --libs hdf5-serial) -lhdf5_hl -lsundials_arkode \
  -lsundials_nvecserial -linih $(pkg-config --libs gsl) -lm -fopenmp"
# shellcheck disable=SC2086
gcc $CFLAGS -Iinclude -Isrc -Ibench/driver $INC \
    bench/driver/g72_support_tiles.c build/libballfilm.a $LIBS \
    -o "$tmp/g72_support_tiles"
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2-)," \
     "load average $(cut -d' ' -f1-3 /proc/loadavg)"
"$tmp/g72_support_tiles" 64 1 4 16 64
"$tmp/g72_support_tiles" 128 1 4 16
"$tmp/g72_support_tiles" 256 1 4
