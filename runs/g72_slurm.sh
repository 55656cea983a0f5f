#!/bin/bash
# Slurm batch script for one Greenspan 1972 run split over MPI ranks on a
# cluster (docs/parallel.md).
#
#   sbatch runs/g72_slurm.sh
#
# Build first with `make mpi` (Open MPI).  Each rank holds and steps the
# particles of its x-slab (and reads a halo from its neighbours); rank 0
# gathers the state at output rows and checkpoints and writes the
# output, bit for bit the file of `bin/ballfilm run` on one process.  The
# checkpoint ([scene] checkpoint_every, and on SIGUSR1, which srun and
# mpirun forward to every rank) continues on any number of ranks: if the
# job hits its time limit, submit the continuation with
#   srun bin/ballfilm-mpi run --restart out/greenspan72_large.h5
# Each rank holds its share (about 450 B a particle, plus its halo); rank
# 0 also holds the whole state (64 B a particle) while it writes a row or
# a checkpoint, and every rank holds the whole initial state (48 B a
# particle) while the run is set up: docs/parallel.md.
#
#SBATCH --job-name=ballfilm-g72
#SBATCH --ntasks=8
#SBATCH --cpus-per-task=1
#SBATCH --mem-per-cpu=2G
#SBATCH --time=01:00:00
#SBATCH --signal=USR1@120
#SBATCH --output=ballfilm-g72-%j.log

set -euo pipefail
cd "${SLURM_SUBMIT_DIR:-.}"
mkdir -p out
srun bin/ballfilm-mpi run runs/greenspan72_large.ini \
    --set scene.checkpoint_every=500 -o out/greenspan72_large.h5
