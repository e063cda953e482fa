#!/usr/bin/env bash
# The workflow through a real Slurm cluster (issue 44): a one-node cluster on this machine (tests/e2e/slurm_cluster.sh)
# runs workflows/Snakefile through the shipped profile (workflows/profiles/slurm) on six simulated captures, three
# F01 and three Illum, plus one corrupt capture. Checked:
#   - every job of every capture ran as a Slurm job: the job completion log names each rule and capture;
#   - the results are byte-identical to a local -j2 run of the same inputs;
#   - the corrupt capture fails only its own job: the others finish (--keep-going) and the index lists it with its
#     one-line error;
#   - a run killed part-way (one running Slurm job cancelled with scancel, then Snakemake killed with SIGKILL) leaves
#     no half-written result, and the next run submits only the captures that were missing.
# Usage (from CTest): slurm_test.sh LFSP_BINARY SOURCE_DIR. Exits 77 (CTest's skip) when the Slurm and munge
# packages are not installed (tools/bootstrap installs them).
set -euo pipefail
lfsp=$1
source_dir=$2
# shellcheck source=slurm_cluster.sh
source "$source_dir/tests/e2e/slurm_cluster.sh"
command -v snakemake > /dev/null || { echo "snakemake is not installed (tools/bootstrap installs it)"; exit 1; }
if ! slurm_cluster_available; then
  echo "SKIPPED: munge, slurmctld, slurmd or slurm-client is not installed (tools/bootstrap installs them)"
  exit 77
fi

tmp=$(mktemp -d)
snakemake_pid=""
cleanup() {
  set +e  # stop everything even if one step fails
  [ -n "$snakemake_pid" ] && kill -9 "$snakemake_pid" 2> /dev/null
  slurm_cluster_stop "$tmp/cluster"
  [ -n "${KEEP_TMP:-}" ] || rm -rf "$tmp"
}
trap cleanup EXIT
fail() {
  echo "FAILED: $*"
  for log in "$tmp"/*.log; do [ -f "$log" ] && { echo "--- $log"; tail -30 "$log"; }; done
  exit 1
}

# Six small captures, three per camera, each with its white images; and a capture cut short (corrupt).
for i in 1 2 3; do
  "$lfsp" -q simulate --camera mini-f01 --scene occluders --seed "$i" --storage uint8 --out "$tmp/sim/f01-$i" \
    > /dev/null &
  "$lfsp" -q simulate --camera mini-illum --scene planes --seed "$i" --storage uint8 --out "$tmp/sim/illum-$i" \
    > /dev/null
  wait
done
for i in 1 2 3; do
  mkdir -p "$tmp/captures/f01-$i" "$tmp/captures/illum-$i"
  cp -r "$tmp/sim/f01-$i/capture.lfp" "$tmp/sim/f01-$i/whites" "$tmp/captures/f01-$i/"
  cp -r "$tmp/sim/illum-$i/capture.LFR" "$tmp/sim/illum-$i/whites" "$tmp/captures/illum-$i/"
done
mkdir -p "$tmp/captures/broken"
head -c 300000 "$tmp/sim/illum-1/capture.LFR" > "$tmp/captures/broken/capture.LFR"
cp -r "$tmp/sim/illum-1/whites" "$tmp/captures/broken/"
good=(f01-1-capture f01-2-capture f01-3-capture illum-1-capture illum-2-capture illum-3-capture)
broken=broken-capture

# workflow FOLDER ARGS...: the Snakefile on the captures, run from $tmp/FOLDER, results in $tmp/results. Both runs
# write to the same results folder (the local one is moved aside after), since the files name their inputs' paths.
workflow() {
  local folder=$1
  shift
  mkdir -p "$tmp/$folder"
  (cd "$tmp/$folder" && exec snakemake -s "$source_dir/workflows/Snakefile" "$@" \
    --config captures="$tmp/captures" out="$tmp/results" lfsp="$lfsp")
}

# The reference: a local run with two cores. The broken capture fails, so the run fails.
if workflow local-run -j2 --keep-going > "$tmp/local.log" 2>&1; then fail "the local run succeeded despite $broken"; fi
mv "$tmp/results" "$tmp/local"
for capture in "${good[@]}"; do test -s "$tmp/local/$capture/report.html" || fail "local run: no report of $capture"; done
echo "local run: ${#good[@]} reports, $broken failed"

slurm_cluster_start "$tmp/cluster" || fail "the test cluster did not start"
echo "cluster: $(sinfo -h -o '%P %D %c CPUs %m MB %T')"
profile=(--profile "$source_dir/workflows/profiles/slurm" --restart-times 0)

# First cluster run, killed part-way: once Snakemake has seen one job finish and another capture's job is running,
# cancel that job (as the scheduler would at a time limit) and kill Snakemake (as a lost login session would).
mkdir -p "$tmp/cluster-run"
(cd "$tmp/cluster-run" && exec snakemake -s "$source_dir/workflows/Snakefile" "${profile[@]}" \
  --config captures="$tmp/captures" out="$tmp/results" lfsp="$lfsp") > "$tmp/cluster-1.log" 2>&1 &
snakemake_pid=$!  # Snakemake itself (exec)
cancelled=""
for ((i = 0; i < 600; i++)); do
  kill -0 "$snakemake_pid" 2> /dev/null || fail "the first cluster run ended before it could be killed"
  if grep -q " steps (.*) done" "$tmp/cluster-1.log" 2> /dev/null; then
    # The job that started last: the most of its steps still to run, so scancel reaches it before it ends.
    cancelled=$(squeue -h -t RUNNING --sort=-S -o '%i %.300j' | grep -v -e ':index' -e ":$broken" | head -1 || true)
    [ -n "$cancelled" ] && break
  fi
  sleep 0.5
done
[ -n "$cancelled" ] || fail "no capture job was running after the first finished"
cancelled=$(echo "$cancelled" | xargs)
scancel "${cancelled%% *}"
kill -9 "$snakemake_pid"
wait "$snakemake_pid" 2> /dev/null || true
snakemake_pid=""
cancelled_capture=${cancelled##*:}
echo "killed the first run; cancelled Slurm job $cancelled"
# The jobs Snakemake had submitted still run; let them end, as a user would before restarting (or scancel them).
for ((i = 0; i < 600; i++)); do
  [ -z "$(squeue -h)" ] && break
  sleep 0.5
done
[ -z "$(squeue -h)" ] || fail "jobs of the killed run are still queued: $(squeue -h)"
# Nothing half-written: every result file present is the reference's, byte for byte.
while IFS= read -r file; do
  cmp -s "$file" "$tmp/local/${file#"$tmp/results/"}" || fail "after the kill, ${file#"$tmp/"} differs from the local run's"
done < <(find "$tmp/results" -name decoded.h5 -o -name disparity.pfm -o -name segmentation.h5 -o -name metrics.json)
last_job=$(sacct --completion -n -X -P -o JobID | sort -n | tail -1)

# Second run: Snakemake's lock of the killed run is released first (--unlock), as README says. What it plans (a dry
# run) is what it then submits: the captures Snakemake had not seen finish, never those it had.
workflow cluster-run "${profile[@]}" --unlock > "$tmp/unlock.log" 2>&1 || fail "snakemake --unlock"
workflow cluster-run "${profile[@]}" -n > "$tmp/plan.log" 2>&1 || fail "the dry run after the kill"
planned=$(grep -o "capture=[A-Za-z0-9-]*" "$tmp/plan.log" | cut -d= -f2 | sort -u | xargs)
kept=()
for capture in "${good[@]}"; do [[ " $planned " == *" $capture "* ]] || kept+=("$capture"); done
echo "after the kill: Slurm jobs 1..$last_job; to redo: $planned; kept: ${kept[*]}"
[ ${#kept[@]} -ge 1 ] || fail "the killed run kept no finished capture"
# What Slurm recorded for the cancelled job: CANCELLED, or COMPLETED in the rare case that it ended between squeue and
# scancel (seen once in CI), when Snakemake may have seen it finish and rightly keeps it.
cancelled_state=$(sacct --completion -n -X -P -o JobID,State | awk -F'|' -v id="${cancelled%% *}" '$1 == id {print $2}')
if [[ "$cancelled_state" == CANCELLED* ]]; then
  [[ " $planned " == *" $cancelled_capture "* ]] || fail "the cancelled $cancelled_capture is not to be redone"
else
  echo "Slurm job ${cancelled%% *} ended $cancelled_state before scancel reached it; $cancelled_capture may be kept"
fi
if workflow cluster-run "${profile[@]}" > "$tmp/cluster-2.log" 2>&1; then fail "the second run succeeded despite $broken"; fi
grep -q "Exiting because a job execution failed" "$tmp/cluster-2.log" || fail "the second run did not end as a failed job"

# The jobs Slurm ran, as its job completion log lists them: "<id>|<name>|<state>".
sacct --completion -n -X -P -o JobID,JobName%300,State > "$tmp/jobs.txt"
awk -F'|' -v last="$last_job" '$1 > last' "$tmp/jobs.txt" > "$tmp/jobs-2.txt"
echo "Slurm jobs: $(wc -l < "$tmp/jobs.txt") in all, $(wc -l < "$tmp/jobs-2.txt") in the second run"
ran() {  # ran RULE CAPTURE: some Slurm job was named lfsp:<rules>:<captures> with both
  awk -F'|' -v rule="$1" -v capture="$2" '{
      split($2, part, ":"); n = split(part[2], rules, ","); m = split(part[3], captures, ",")
      r = 0; c = 0
      for (i = 1; i <= n; i++) if (rules[i] == rule) r = 1
      for (i = 1; i <= m; i++) if (captures[i] == capture) c = 1
      if (r && c) found = 1 } END { exit !found }' "$tmp/jobs.txt"
}
for capture in "${good[@]}"; do
  for rule in decode depth segment report; do
    ran "$rule" "$capture" || fail "no Slurm job ran $rule of $capture"
  done
done
# Every job completed but the cancelled one and the broken capture's (one per run).
unexpected=$(grep -v -e "^${cancelled%% *}|.*|CANCELLED" -e ":$broken|FAILED$" -e "|COMPLETED$" "$tmp/jobs.txt" || true)
[ -z "$unexpected" ] || fail "Slurm jobs that neither completed nor were expected to fail: $unexpected"
grep -q '|lfsp:index|COMPLETED$' "$tmp/jobs.txt" && fail "the index ran although $broken failed"
grep -q "lfsp:decode.*:$broken|FAILED" "$tmp/jobs.txt" || fail "the Slurm job of $broken did not fail"
echo "every rule of every good capture ran as a Slurm job; all jobs completed but the cancelled one and $broken's"
# Only what was missing: the second run's jobs are the planned captures, none of the kept ones.
submitted=$(cut -d'|' -f2 "$tmp/jobs-2.txt" | grep -v '^lfsp:index$' | sed 's/.*://' | tr ',' '\n' | sort -u | xargs)
[ "$submitted" = "$planned" ] || fail "the second run submitted captures '$submitted', planned '$planned'"
echo "the second run submitted only the missing captures ($submitted); ${kept[*]} were kept"

# Results: byte-identical to the local run; the index lists every good capture and the broken one with its error.
for capture in "${good[@]}"; do
  for file in decoded.h5 disparity.pfm segmentation.h5 metrics.json; do
    cmp -s "$tmp/results/$capture/$file" "$tmp/local/$capture/$file" ||
      fail "$capture/$file differs between the cluster and the local run"
  done
  grep -q "href=\"$capture/report.html\"" "$tmp/results/index.html" || fail "the index does not link $capture"
done
error=$(grep -o "FAILED: decode failed: [^<]*" "$tmp/results/index.html") || fail "the index does not show $broken's error"
grep -q "<td>$broken</td><td[^>]*>FAILED" "$tmp/results/index.html" || fail "the index's failed row is not $broken's"
echo "results identical to the local run; the index shows $broken: $error"
if find "$tmp/results" \( -name '*.partial' -o -name '*.tmp-*' \) | grep -q .; then
  fail "temporary files were left: $(find "$tmp/results" -name '*.partial' -o -name '*.tmp-*')"
fi
echo "PASSED"
