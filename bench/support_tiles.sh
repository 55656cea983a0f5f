#!/usr/bin/env bash
# bench/support_tiles.sh: the support-set gravity's fast method on one
# local configuration copied side by side in x 1 to 64 times (Greenspan
# 1972 benchmark scene at n = 64, 128 and 256 after 100 steps), so that N
# grows from 4096 to 262144 with the same work per particle: does the time
# per particle grow when the arrays outgrow the caches?  (docs/performance.md,
# "Support-set gravity: the 2x goal".)  bench/driver/g72_support_tiles.c
# says what is measured.  Run by make bench (about 10 s).
# Builds build/libballfilm.a first.
set -euo pipefail
cd "$(dirname "$0")/.."
tmp=$(mktemp -d /tmp/ballfilm-support-tiles.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
. bench/driver/build.sh
driver_library "$tmp/build.log"
# shellcheck disable=SC2086
gcc $DRIVER_CFLAGS -Iinclude -Isrc -Ibench/driver $DRIVER_INC \
    bench/driver/g72_support_tiles.c build/libballfilm.a $DRIVER_LIBS \
    -o "$tmp/g72_support_tiles"
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2-)," \
     "load average $(cut -d' ' -f1-3 /proc/loadavg)"
"$tmp/g72_support_tiles" 64 1 4 16 64
"$tmp/g72_support_tiles" 128 1 4 16
"$tmp/g72_support_tiles" 256 1 4
