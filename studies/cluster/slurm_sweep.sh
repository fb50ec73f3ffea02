#!/usr/bin/env bash
# A study on a Slurm cluster: one shard per array task, then the merge as a job that waits
# for all of them. Run from the repository root, on a shared file system, after
# `cargo build --release` (docs/studies.md, On a cluster):
#
#   STUDY=studies/monte_carlo.toml SHARDS=8 sbatch --array=0-7 studies/cluster/slurm_sweep.sh
#   # then, once (Slurm starts it when every task of the array has ended):
#   sbatch --dependency=afterany:<array job id> --wrap \
#     "target/release/wingman sweep merge runs/monte_carlo-shard-*-of-8 --out runs/monte_carlo"
#
# A task exits 1 when a case of its shard could not run (a node without a graphics adapter)
# and is then simply submitted again (`--array=<its index>`), as is a task that was killed or
# cut off: the shard runs again what has no result and skips the cases it completed. The merge
# names any case still missing or without a result.
#
# Slurm opens the log before the script starts and does not make its folder: the log goes to
# the folder the job was submitted from (the repository root), which exists.
#SBATCH --job-name=wingman-sweep
#SBATCH --cpus-per-task=4
#SBATCH --mem=8G
#SBATCH --time=02:00:00
#SBATCH --output=wingman-sweep-%A_%a.log
set -euo pipefail

: "${STUDY:?set STUDY to the study file, e.g. studies/monte_carlo.toml}"
: "${SHARDS:?set SHARDS to the number of array tasks}"
INDEX="${SLURM_ARRAY_TASK_ID:?submit with sbatch --array=0-$((SHARDS - 1))}"
NAME="$(basename "$STUDY" .toml)"
WINGMAN="${WINGMAN:-target/release/wingman}" # or `wingman` after `cargo install --path .`
RUNS="${RUNS:-runs}"                         # the folder of the shards' folders

export NODEVICE_SELECT=1 # quiet Mesa's lavapipe on nodes without a GPU
mkdir -p "$RUNS"
exec "$WINGMAN" sweep "$STUDY" \
    --shard "$INDEX/$SHARDS" \
    --jobs "${SLURM_CPUS_PER_TASK:-1}" \
    --out "$RUNS/$NAME-shard-$INDEX-of-$SHARDS"
