#!/usr/bin/env bash
# bench/mac_vs_plain.sh: the thesis's MAC reservoir at refine 4 (800 steps,
# the 4x case of `make stratres`) run by ballfilm against
# bench/plain_mac.c, the same algorithm written as a straightforward C
# program, compiled here twice: gcc -O2 and gcc -O2 -march=native (both
# with the project's -std=c11 -ffp-contract=off: contracting a*b+c into
# one rounding would change which cell a marker lands in, so the two
# programs would no longer do the same run).  The three run in turn,
# 5 times each; printed: each one's shortest CPU time (user + system of
# the whole process), the median of the 5 ratios ballfilm / plain of each
# round (goal <= 0.8 against -march=native, issue 21 item 4), and whether
# every output row of both plain builds equals ballfilm's to the last bit
# (fields, markers, counts, masses, diagnostics).  Run by make bench.
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p build/bench
std="-std=c11 -Wall -Wextra -Werror -ffp-contract=off"
gcc $std -O2 -o build/bench/plain_mac_O2 bench/plain_mac.c -lm
gcc $std -O2 -march=native -o build/bench/plain_mac_native bench/plain_mac.c -lm
tmp=$(mktemp -d /tmp/ballfilm-bench-mac.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
/usr/bin/python3 - bin/ballfilm build/bench/plain_mac_O2 \
    build/bench/plain_mac_native "$tmp" <<'PY'
import os, resource, statistics, subprocess, sys
import h5py, numpy as np
prog, plain_o2, plain_nat, tmp = sys.argv[1:5]
h5 = os.path.join(tmp, "b.h5")
ours = [prog, "run", "runs/stratres.ini", "-q", "-o", h5,
        "--set", "mac.refine=4", "--set", "scene.dt=0.0125",
        "--set", "scene.output_every=40", "--set", "mac.void_fix=true"]
plain_args = ["4", "0.0125", "10", "40"]
runs = {"ballfilm": ours,
        "-O2": [plain_o2, os.path.join(tmp, "o2.bin")] + plain_args,
        "-O2 -march=native": [plain_nat, os.path.join(tmp, "nat.bin")]
                             + plain_args}

def cpu(cmd):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    r = subprocess.run(cmd, capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if r.returncode:
        sys.exit("failed: %s\n%s" % (" ".join(cmd), r.stderr))
    return (after.ru_utime - before.ru_utime +
            after.ru_stime - before.ru_stime)

times = {k: [] for k in runs}
for _ in range(5):
    for k, cmd in runs.items():
        times[k].append(cpu(cmd))

# every row of the plain program's binary output against ballfilm's HDF5
f = h5py.File(h5, "r")
ni, nj = int(f["/mac/grid"][0]), int(f["/mac/grid"][1])
slots = f["/mac/particles/x"].shape[1]
layout = [("/mac/u", (ni + 1) * nj, "<f8"), ("/mac/v", ni * (nj + 1), "<f8"),
          ("/mac/p", ni * nj, "<f8"), ("/mac/rho", ni * nj, "<f8"),
          ("/mac/T", ni * nj, "<f8"), ("/mac/flags", ni * nj, "<i8"),
          ("/mac/particles/x", slots, "<f8"),
          ("/mac/particles/y", slots, "<f8"),
          ("/mac/particles/density", slots, "<f8"),
          ("/mac/particles/flag", slots, "<i8"), ("/mac/counts", 8, "<i8"),
          ("/mac/mass", 4, "<f8"), ("/mac/diag", 6, "<f8")]
rowbytes = 8 * sum(n for _, n, _ in layout)

def same(binfile):
    raw = open(binfile, "rb").read()
    nrows = f["/mac/u"].shape[0]
    if len(raw) != nrows * rowbytes:
        return False
    off = 0
    for r in range(nrows):
        for name, n, dt in layout:
            a = np.frombuffer(raw, dtype=dt, count=n, offset=off)
            off += 8 * n
            b = np.ascontiguousarray(f[name][r], dtype=dt)
            if a.tobytes() != b.tobytes():
                return False
    return True

diag, counts = f["/mac/diag"][-1], f["/mac/counts"][-1]
print("MAC reservoir, refine 4 (58 x 58 cells, 800 steps, void_fix): ballfilm "
      "against a plain C program (bench/plain_mac.c), 5 rounds, CPU time")
cpuinfo = [l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo")
           if l.startswith("model name")]
print("  machine: %s x %d, load average %s" % (cpuinfo[0], len(cpuinfo),
      " ".join(open("/proc/loadavg").read().split()[:3])))
print("  ballfilm: %.3f s   plain -O2: %.3f s   plain -O2 -march=native: "
      "%.3f s   (shortest)" % (min(times["ballfilm"]), min(times["-O2"]),
                              min(times["-O2 -march=native"])))
for k in ("-O2", "-O2 -march=native"):
    q = [b / p for b, p in zip(times["ballfilm"], times[k])]
    print("  ballfilm / plain %-17s median %.2f (range %.2f-%.2f)%s"
          % (k + ":", statistics.median(q), min(q), max(q),
             "   goal <= 0.8" if "native" in k else ""))
print("  same results (every row of %d: fields, %d markers, counts; %d "
      "entered, %d into the sink, max |u| %.4g): -O2 %s, -march=native %s"
      % (f["/mac/u"].shape[0], slots, counts[4], counts[5], diag[0],
         "yes" if same(runs["-O2"][1]) else "NO",
         "yes" if same(runs["-O2 -march=native"][1]) else "NO"))
PY
