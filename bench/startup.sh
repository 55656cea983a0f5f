#!/usr/bin/env bash
# bench/startup.sh: what a small run costs before and around its first
# step.  A one-ball scene of 10 steps with its output file is run 30 times;
# prints the shortest wall time and the peak resident memory (goal: under
# 10 ms and 10 MiB, issue 21), and the shared objects the program loads.
# Alternated with those runs, a process that does nothing (/bin/true): the
# floor of starting any process on this machine at this moment (on a
# virtual machine it moves by milliseconds from one minute to the next).
# Then 10^4 such cases as one sweep in one process (ballfilm sweep, each
# case writing its own file; about half a minute): the time per case, to
# set against a process per case.  Absolute times depend on the machine:
# the CPU model and the load are printed with them.  Run by make bench.
#
#   bench/startup.sh [PROGRAM]   (default bin/ballfilm; another build of
#                                 the program, to compare on one machine)
set -euo pipefail
shown=${1:-bin/ballfilm}
prog=$shown
if [ -e "$prog" ]; then prog=$(realpath "$prog"); fi
cd "$(dirname "$0")/.."
tmp=$(mktemp -d /tmp/ballfilm-bench-startup.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/tiny.ini" <<'INI'
[scene]
effects = gravity floor
dt = 1e-4
t_end = 1e-3
[ball.1]
position = 1
INI
/usr/bin/python3 - "$prog" "$tmp" "$shown" <<'PY'
import os, subprocess, sys, time
prog, tmp, shown = sys.argv[1], sys.argv[2], sys.argv[3]
cmd = [prog, "run", os.path.join(tmp, "tiny.ini"), "-q", "-o",
       os.path.join(tmp, "tiny.h5")]
best, peak, floor = float("inf"), 0.0, float("inf")
for _ in range(30):
    t0 = time.perf_counter()
    subprocess.run(["/bin/true"])
    floor = min(floor, time.perf_counter() - t0)
    t0 = time.perf_counter()
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    best = min(best, time.perf_counter() - t0)
    if r.returncode:
        sys.exit("startup: the run failed: " + r.stderr.decode())
    # the program's own peak (VmHWM), from its summary
    for line in r.stdout.decode().splitlines():
        if line.startswith("peak memory:"):
            peak = max(peak, float(line.split()[2]))
libs = subprocess.run(["ldd", prog], capture_output=True, text=True).stdout
nlib = sum(1 for l in libs.splitlines() if "=>" in l or l.strip().startswith("/"))
cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo")
            if l.startswith("model name")), "unknown CPU")
load = open("/proc/loadavg").read().split()[0]
print("start-up of a small run (1 ball, 10 steps, output file), 30 runs of %s" % shown)
print("  shortest wall time: %6.1f ms   (goal < 10 ms)" % (best * 1e3))
print("  peak resident set:  %6.1f MiB  (goal < 10 MiB)" % peak)
print("  shared objects loaded: %d" % nlib)
print("  /bin/true alternated with it: %4.1f ms (starting any process here, now)"
      % (floor * 1e3))
# a sweep of 10^4 tiny cases in one process
ncase = 10000
sweep = [prog, "sweep", os.path.join(tmp, "tiny.ini"), "--vary",
         "ball.1.position=1:2:%d" % ncase, "-o", os.path.join(tmp, "sweep"),
         "-q"]
t0 = time.perf_counter()
r = subprocess.run(sweep, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
wall = time.perf_counter() - t0
if r.returncode:
    why = r.stderr.decode().strip().splitlines() or ["exit status %d"
                                                      % r.returncode]
    print("  sweep of %d such cases: failed: %s" % (ncase, why[-1]))
else:
    print("  sweep of %d such cases in one process: %.1f s, %.2f ms a case "
          "(each writes its file)" % (ncase, wall, wall / ncase * 1e3))
print("  machine: %s, %d cores, load average %s" % (cpu, os.cpu_count(), load))
PY
