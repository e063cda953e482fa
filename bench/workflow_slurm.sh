#!/usr/bin/env bash
# The workflow on N small simulated captures (half F01, half Illum) locally with -j2 and through the one-node test
# Slurm cluster (tests/e2e/slurm_cluster.sh) with the shipped profile, one capture per Slurm job and then
# --group-components capture=GROUP; prints a row per run for BENCHMARKS.md ("Workflow on a Slurm cluster").
# Usage: bench/workflow_slurm.sh [LFSP_BINARY [N [GROUP]]]   (defaults: build/apps/lfsp, 24, 4)
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
lfsp=$(realpath "${1:-build/apps/lfsp}")
n=${2:-24}
group=${3:-4}
source tests/e2e/slurm_cluster.sh
tmp=$(mktemp -d)
trap 'slurm_cluster_stop "$tmp/cluster"; rm -rf "$tmp"' EXIT

for ((i = 1; i <= n / 2; i++)); do
  "$lfsp" -q simulate --camera mini-f01 --scene occluders --seed "$i" --storage uint8 --out "$tmp/captures/f01-$i" \
    > /dev/null &
  "$lfsp" -q simulate --camera mini-illum --scene planes --seed "$i" --storage uint8 --out "$tmp/captures/illum-$i" \
    > /dev/null
  wait
done
rm -rf "$tmp"/captures/*/ground_truth

run() {  # run LABEL OUT ARGS...: one workflow run, timed; prints LABEL | wall s | Slurm jobs
  local label=$1 out=$2
  shift 2
  local before after start end
  before=$( (sacct --completion -n -X -P -o JobID 2> /dev/null || true) | wc -l)
  start=$(date +%s%N)
  (cd "$tmp" && snakemake -s "$repo/workflows/Snakefile" "$@" \
    --config captures="$tmp/captures" out="$tmp/$out" lfsp="$lfsp") > "$tmp/$out.log" 2>&1 ||
    { tail -30 "$tmp/$out.log"; exit 1; }
  end=$(date +%s%N)
  after=$( (sacct --completion -n -X -P -o JobID 2> /dev/null || true) | wc -l)
  printf '| %s | %d | %d.%d | %d |\n' "$label" "$n" $(((end - start) / 1000000000)) \
    $(((end - start) / 100000000 % 10)) $((after - before))
}

echo "| run | captures | wall s | Slurm jobs |"
echo "|---|---|---|---|"
run "local -j2" local -j2
slurm_cluster_start "$tmp/cluster" > /dev/null
profile=(--profile "$repo/workflows/profiles/slurm" --restart-times 0)
run "Slurm, one capture per job" slurm1 "${profile[@]}"
run "Slurm, --group-components capture=$group" slurm$group "${profile[@]}" --group-components "capture=$group"
