#!/usr/bin/env bash
# bench/g72_vs_a752c43.sh: the Greenspan 1972 step at N = 65536 and 262144
# now against main at a752c43 (before issue 21 item 5), both measured here,
# in this run, on this machine.
#
# The library of a752c43 is built from this repository's history (git
# archive; needs the commit, so a full clone) in a temporary directory;
# bench/driver/g72_steps.c is built against it and against build/
# libballfilm.a (brought up to date first).  The two run alternately (the
# order swapped in every pair), 5 pairs at N = 65536 and 3 at N = 262144;
# each run takes 100 warm-up steps, then the shortest of 3 runs of 20
# steps, in CPU time of the process (one thread), and then the support-set
# gravity alone on the state reached (shortest of 5 evaluations).
# Printed: each one's median particle-steps per second, the median of
# the pairwise speed-ups of the step and of the support-set gravity alone
# (a752c43 time / now; goal 2, issue 21 item 5) and whether the two end
# in the same positions and the same g, bit for bit (they must: every
# change since was made with the same arithmetic).
# Run by make bench (about 3 minutes, most of it the old library's build).
set -euo pipefail
cd "$(dirname "$0")/.."
OLD=a752c43
if ! git cat-file -e "$OLD^{commit}" 2>/dev/null; then
    echo "g72_vs_a752c43: commit $OLD is not in this clone (a shallow one?);"
    echo "  fetch the history (git fetch --unshallow) to compare against it"
    exit 0
fi
tmp=$(mktemp -d /tmp/ballfilm-bench-g72.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
mkdir "$tmp/old"
git archive "$OLD" | tar -x -C "$tmp/old"
. bench/driver/build.sh
echo "building the library of $OLD in $tmp/old ..."
driver_library "$tmp/old-build.log" "$tmp/old"
driver_library "$tmp/build.log"
# shellcheck disable=SC2086
gcc $DRIVER_CFLAGS -I"$tmp/old/include" -I"$tmp/old/src" $DRIVER_INC \
    bench/driver/g72_steps.c "$tmp/old/build/libballfilm.a" $DRIVER_LIBS \
    -o "$tmp/old_steps"
# shellcheck disable=SC2086
gcc $DRIVER_CFLAGS -Iinclude -Isrc $DRIVER_INC bench/driver/g72_steps.c \
    build/libballfilm.a $DRIVER_LIBS -o "$tmp/new_steps"
/usr/bin/python3 - "$tmp/old_steps" "$tmp/new_steps" "$OLD" <<'PY'
import re, statistics, subprocess, sys
old, new, name = sys.argv[1:4]

def run(prog, n):
    out = subprocess.run([prog, str(n)], capture_output=True, text=True,
                         check=True).stdout
    m = re.search(r"s_per_step=(\S+) s_support=(\S+) hash=(\S+) "
                  r"ghash=(\S+)", out)
    return float(m.group(1)), float(m.group(2)), m.group(3) + m.group(4)

print("Greenspan 1972 at large N: now against main at %s, both built and "
      "run here, alternately (one thread, CPU time)" % name)
print("%8s %15s %15s %19s %19s %5s"
      % ("N", name + " part-st/s", "now part-st/s", "step speed-up",
         "support speed-up", "same"))
for n, pairs in ((256, 5), (512, 3)):
    N = n * n
    to, tn, sp, ss, same = [], [], [], [], True
    for k in range(pairs):
        if k % 2 == 0:
            a, sa, ha = run(old, n); b, sb, hb = run(new, n)
        else:
            b, sb, hb = run(new, n); a, sa, ha = run(old, n)
        to.append(a); tn.append(b); sp.append(a / b); ss.append(sa / sb)
        same &= ha == hb
    print("%8d %15.3g %15.3g %7.2f (%.2f-%.2f) %7.2f (%.2f-%.2f) %5s"
          % (N, N / statistics.median(to), N / statistics.median(tn),
             statistics.median(sp), min(sp), max(sp),
             statistics.median(ss), min(ss), max(ss),
             "yes" if same else "NO"))
print("(speed-ups: medians of the pairs, range in brackets; goal of issue "
      "21 item 5: 2 at both sizes)")
PY
