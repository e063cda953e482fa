#!/usr/bin/env bash
# The Snakemake workflow (workflows/Snakefile) on three bundled captures with -j2 (issue 17): every report and the
# index are written; a second run does nothing; touching one capture reruns only that capture's jobs (and the index).
# Usage (from CTest): workflow_test.sh LFSP_BINARY SOURCE_DIR
set -euo pipefail
lfsp=$1
source_dir=$2
command -v snakemake > /dev/null || { echo "snakemake is not installed (tools/bootstrap installs it)"; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAILED: $*"; exit 1; }

mkdir -p "$tmp/captures/a" "$tmp/captures/b" "$tmp/captures/c"
cp -r "$source_dir/samples/mini-illum/capture.LFR" "$source_dir/samples/mini-illum/whites" "$tmp/captures/a/"
cp -r "$source_dir/samples/mini-f01/capture.lfp" "$source_dir/samples/mini-f01/whites" "$tmp/captures/b/"
cp -r "$source_dir/samples/mini-illum/capture.LFR" "$source_dir/samples/mini-illum/whites" "$tmp/captures/c/"

run() {
  snakemake -s "$source_dir/workflows/Snakefile" --directory "$tmp" "$@" \
    --config captures="$tmp/captures" out="$tmp/results" lfsp="$lfsp"
}

run -j2 -q > "$tmp/first.log" 2>&1 || { cat "$tmp/first.log"; fail "the first run"; }
for capture in a-capture b-capture c-capture; do
  test -s "$tmp/results/$capture/report.html" || fail "no report for $capture"
  grep -q "href=\"$capture/report.html\"" "$tmp/results/index.html" || fail "the index does not list $capture"
done
echo "first run: 3 reports and the index"

run -n > "$tmp/second.log" 2>&1 || { cat "$tmp/second.log"; fail "the dry second run"; }
grep -q "Nothing to be done" "$tmp/second.log" || { cat "$tmp/second.log"; fail "a second run would redo work"; }
echo "second run: nothing to be done"

sleep 1
touch "$tmp/captures/b/capture.lfp"
run -n > "$tmp/third.log" 2>&1 || { cat "$tmp/third.log"; fail "the dry run after touching b"; }
grep -q "capture=b-capture" "$tmp/third.log" || { cat "$tmp/third.log"; fail "touching b reruns none of its jobs"; }
if grep -q -E "capture=(a|c)-capture" "$tmp/third.log"; then cat "$tmp/third.log"; fail "touching b reruns a or c"; fi
for rule in decode depth segment report index; do
  grep -q "^rule $rule:" "$tmp/third.log" || { cat "$tmp/third.log"; fail "touching b does not rerun $rule"; }
done
echo "after touching b: only b's decode, depth, segment, report and the index"
