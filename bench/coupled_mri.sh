#!/usr/bin/env bash
# bench/coupled_mri.sh: the two multirate methods of the coupled model at
# equal error (issue 19): [coupled] film_every (the split scheme, the film
# stepping every K ball steps; K = 1 is the paper's single rate, auto the
# adaptive choice) against ARKODE's MRIStep ([coupled] scheme = mri: the
# film the slow part at the fixed step dt, the balls the fast part by an
# adaptive inner ERK), both measured by `ballfilm converge` against ARKODE
# on the whole system (scheme = arkode, rtol 1e-12) over the first 0.25 s
# of runs/coupled_fig8.ini (four contacts).  Printed: for each accuracy of
# the balls' x at T and of the film's phase flux q_d at T, the cheapest
# run (wall time of the stepping loop, minimum of 2 repeats) of each
# method, and MRI's cost over the cheapest film_every.  Run by make bench.
set -euo pipefail
cd "$(dirname "$0")/.."
tmp=$(mktemp -d /tmp/ballfilm-bench-mri.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
scene=runs/coupled_fig8.ini
bin/ballfilm converge "$scene" -q --t-end 0.25 --repeats 2 \
    --methods mv2m,mv2m:film_every=10,mv2m:film_every=auto \
    --dt 4e-5,2e-5,1e-5,5e-6 -o "$tmp/split.h5" >/dev/null
bin/ballfilm converge "$scene" -q --t-end 0.25 --repeats 2 \
    --methods mri,mri:rtol=1e-10 \
    --dt 8e-4,4e-4,2e-4,1e-4 -o "$tmp/mri.h5" >/dev/null
/usr/bin/python3 - "$tmp/split.h5" "$tmp/mri.h5" <<'PY'
import sys
import h5py
import numpy as np

def rows(path):
    with h5py.File(path, "r") as f:
        c = f["converge"]
        groups = f["converge"].attrs["groups"]
        groups = (groups.decode() if isinstance(groups, bytes)
                  else str(groups)).split(",")
        methods = f.attrs["methods"]
        methods = (methods.decode() if isinstance(methods, bytes)
                   else str(methods)).split(",")
        ref = np.array(f["reference/estimated_error"])
        out = []
        for k in range(len(c["method"])):
            if int(c["status"][k]) != 0:
                continue
            out.append((methods[int(c["method"][k])], float(c["dt"][k]),
                        np.array(c["error"][k]), float(c["wall"][k])))
        return groups, ref, out

groups, ref, split = rows(sys.argv[1])
_, ref2, mri = rows(sys.argv[2])
print("coupled multirate at equal error: runs/coupled_fig8.ini, T = 0.25 s, "
      "against ARKODE on the whole system (rtol 1e-12)")
for name, accs in (("x", (1e-6, 1e-7, 1e-8)), ("q_d", (1e-7, 1e-8, 1e-9))):
    g = groups.index(name)
    print("  reference's estimated error in %s: %.2g" % (name, max(ref[g], ref2[g])))
    for acc in accs:
        best = {}
        for m, dt, err, wall in split + mri:
            if err[g] <= acc and (m not in best or wall < best[m][1]):
                best[m] = (dt, wall)
        line = "  %-4s <= %.0e:" % (name, acc)
        for m in ("mv2m", "mv2m:film_every=10", "mv2m:film_every=auto",
                  "mri", "mri:rtol=1e-10"):
            line += ("  %s -" % m if m not in best else
                     "  %s %.3g s (dt %.3g)" % (m, best[m][1], best[m][0]))
        fe = [best[m][1] for m in best if m.startswith("mv2m")]
        mr = [best[m][1] for m in best if m.startswith("mri")]
        if fe and mr:
            line += "  | mri / film_every %.3g" % (min(mr) / min(fe))
        print(line)
PY
