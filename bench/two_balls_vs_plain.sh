#!/usr/bin/env bash
# bench/two_balls_vs_plain.sh: `ballfilm run runs/two_balls_B.ini` as
# shipped (10^7 MV2M steps, the energy after every step, the return map,
# output every 100 steps) against bench/plain_two_balls.c, the same work
# written as a straightforward C program (no library, stdio output).  The
# two run alternately, 7 times each; printed: each one's shortest CPU time
# (user + system of the whole process) and the median of the 7 pairwise
# ratios ballfilm/plain (goal <= 1.0, issue 21).  Both must report the same
# number of return-map points and the same largest energy error (the same
# arithmetic in the same order).  Run by make bench.
set -euo pipefail
cd "$(dirname "$0")/.."
tmp=$(mktemp -d /tmp/ballfilm-bench-plain.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
/usr/bin/python3 - bin/ballfilm build/bench/plain_two_balls "$tmp" <<'PY'
import os, re, resource, statistics, subprocess, sys
prog, plain, tmp = sys.argv[1:4]
ours = [prog, "run", "runs/two_balls_B.ini", "-q", "-o", os.path.join(tmp, "b.h5")]
theirs = [plain, os.path.join(tmp, "p.bin")]

def cpu(cmd):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    r = subprocess.run(cmd, capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if r.returncode:
        sys.exit("failed: %s\n%s" % (" ".join(cmd), r.stderr))
    return (after.ru_utime - before.ru_utime +
            after.ru_stime - before.ru_stime), r.stdout

ratios, tb, tp = [], [], []
for _ in range(7):
    b, out_b = cpu(ours)
    p, out_p = cpu(theirs)
    tb.append(b); tp.append(p); ratios.append(b / p)
pts_b = re.search(r"return map: +(\d+) points", out_b).group(1)
err_b = re.search(r"max relative energy error: (\S+)", out_b).group(1)
m = re.search(r"(\d+) return-map points, max relative energy error (\S+)", out_p)
same = (pts_b, err_b) == (m.group(1), m.group(2))
print("runs/two_balls_B.ini as shipped: ballfilm against a plain C program "
      "(bench/plain_two_balls.c), 7 alternating pairs, CPU time")
print("  ballfilm: %.3f s   plain C: %.3f s   (shortest)" % (min(tb), min(tp)))
print("  ballfilm / plain C: median %.2f (range %.2f-%.2f)   goal <= 1.0"
      % (statistics.median(ratios), min(ratios), max(ratios)))
print("  same results (%s return-map points, max energy error %s): %s"
      % (pts_b, err_b, "yes" if same else "NO"))
PY
