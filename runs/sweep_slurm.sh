#!/bin/bash
# Slurm batch script for a ballfilm parameter sweep on a cluster.
#
#   sbatch runs/sweep_slurm.sh
#
# Build first with `make mpi` (OpenMPI).  Rank 0 hands out case numbers on
# request and also computes cases in a second thread, so every rank works;
# cases differ in cost (chaotic runs, failing cases), and dynamic hand-out
# keeps all ranks busy until the queue is empty.  Each case writes its own
# serial HDF5 file into the output directory (on a shared file system, all
# in one place; otherwise each node keeps its own) and rank 0 gathers the
# summary rows into DIR/summary.h5 and DIR/summary.csv.  If the job hits its
# time limit, submit it again: finished cases (those with a case_N.done row)
# are skipped, only the missing ones run.
#
#SBATCH --job-name=ballfilm-sweep
#SBATCH --ntasks=64
#SBATCH --cpus-per-task=1
#SBATCH --time=02:00:00
#SBATCH --output=ballfilm-sweep-%j.log

set -euo pipefail
cd "${SLURM_SUBMIT_DIR:-.}"
srun bin/ballfilm-mpi sweep runs/two_balls_A.ini \
    --vary ball.1.mass=0.5:2.0:64 \
    --set scene.t_end=200 --set scene.output_every=1000 \
    -o out/mass_ratio_sweep
