#!/usr/bin/env bash
# The workflow on every input kind `lfsp` reads (issue 44), found under one folder, with -j2:
#   bundled samples: an F01 .lfp and an Illum .LFR (decoded), an .h5 bundle and the same light field as a .mat, an
#   HCI-style views folder with ground truth (input_CamNNN.png, parameters.cfg, gt_disp_lowres.pfm) and a
#   <row>_<col>.png views folder (not decoded);
#   shared real data ($LFSP_SHARED_DATA, else ../shared/data beside the source; without it the bundled part runs and
#   the test reports skipped): HCI antinous, the Illum views named <row>_<col>, LFToolbox's F01
#   views and a real F01 raw frame (IMG_1.jpg) with camera.txt saying f01.
# Checked: a decode only for containers and raw frames; a report for every input and an index listing all; for HCI
# scenes the benchmark's submission layout (disp_maps/<scene>.pfm = the disparity, runtimes/<scene>.txt) and the
# scores against the ground truth.
# Usage (from CTest): workflow_inputs_test.sh LFSP_BINARY SOURCE_DIR
set -euo pipefail
lfsp=$1
source_dir=$2
shared="${LFSP_SHARED_DATA:-$source_dir/../shared/data}"  # as the C++ tests find it
command -v snakemake > /dev/null || { echo "snakemake is not installed (tools/bootstrap installs it)"; exit 1; }
tmp=$(mktemp -d)
trap '[ -n "${KEEP_TMP:-}" ] || rm -rf "$tmp"' EXIT
fail() { [ -f "$tmp/run.log" ] && tail -40 "$tmp/run.log"; echo "FAILED: $*"; exit 1; }

in=$tmp/inputs
mkdir -p "$in/f01" "$in/illum" "$in/bundles"
cp -r "$source_dir/samples/mini-f01/capture.lfp" "$source_dir/samples/mini-f01/whites" "$in/f01/"
cp -r "$source_dir/samples/mini-illum/capture.LFR" "$source_dir/samples/mini-illum/whites" "$in/illum/"
cp "$source_dir/samples/ideal/ideal.h5" "$in/bundles/ideal.h5"
"$lfsp" -q convert "$in/bundles/ideal.h5" "$in/bundles/ideal_mat.mat"
"$lfsp" -q convert "$in/bundles/ideal.h5" "$in/scenes/ideal"          # HCI naming: input_CamNNN.png
"$lfsp" -q convert "$in/bundles/ideal.h5" "$in/scenes/ideal/gt_disp_lowres.pfm"
test -f "$in/scenes/ideal/parameters.cfg" || fail "lfsp convert wrote no parameters.cfg"
rm -f "$in"/scenes/ideal/*.json  # convert's summary: not part of an HCI scene
mkdir -p "$in/rowcol"
for file in "$in"/scenes/ideal/input_Cam*.png; do  # 7x7 views: camera c is row c/7, column c%7
  c=$((10#$(basename "$file" .png | sed 's/input_Cam//')))
  cp "$file" "$in/rowcol/$((c / 7))_$((c % 7)).png"
done
decoded=(f01-capture illum-capture)
not_decoded=(bundles-ideal bundles-ideal_mat scenes-ideal rowcol)
declare -A scenes=([ideal]=scenes-ideal)  # HCI scene -> its capture
# Largest BadPix 0.07 (%) accepted per scene: measured 27.2 on the 7x7 128x128 8-bit sample (the same as its .h5
# bundle reads) and 5.7 on HCI antinous (BENCHMARKS.md); a run that scores above these is broken.
declare -A badpix_limit=([ideal]=35 [antinous]=10)
if [ -d "$shared" ]; then
  mkdir -p "$in/shared/raw"
  ln -s "$shared/hci/antinous" "$in/shared/antinous"
  ln -s "$shared/lytro_views/illum_field" "$in/shared/illum_field"
  ln -s "$shared/lytro_views/f01_lftoolbox/IMG_0001" "$in/shared/lftoolbox"
  ln -s "$shared/lytro_raw/tao_f01/IMG_1.jpg" "$in/shared/raw/IMG_1.jpg"
  echo f01 > "$in/shared/raw/camera.txt"
  decoded+=(shared-raw-IMG_1)
  not_decoded+=(shared-antinous shared-illum_field shared-lftoolbox)
  scenes[antinous]=shared-antinous
  echo "with the shared real data in $shared"
else
  echo "shared data ($shared) absent: its inputs are left out, and the test ends as skipped (77)"
fi

(cd "$tmp" && snakemake -s "$source_dir/workflows/Snakefile" -j2 \
  --config captures="$in" out="$tmp/results" lfsp="$lfsp") > "$tmp/run.log" 2>&1 || fail "the workflow run"

for capture in "${decoded[@]}" "${not_decoded[@]}"; do
  test -s "$tmp/results/$capture/report.html" || fail "no report of $capture"
  grep -q "href=\"$capture/report.html\"" "$tmp/results/index.html" || fail "the index does not list $capture"
done
for capture in "${decoded[@]}"; do test -s "$tmp/results/$capture/decoded.h5" || fail "$capture was not decoded"; done
for capture in "${not_decoded[@]}"; do
  test -e "$tmp/results/$capture/decoded.h5" && fail "$capture, already a light field, was decoded"
done
count=$(grep -o "<tr><td><a href" "$tmp/results/index.html" | wc -l)
[ "$count" -eq $((${#decoded[@]} + ${#not_decoded[@]})) ] || fail "the index lists $count inputs"
echo "${#decoded[@]} decoded and ${#not_decoded[@]} already decoded inputs: reports and index"

for scene in "${!scenes[@]}"; do
  capture=${scenes[$scene]}
  cmp -s "$tmp/results/hci/disp_maps/$scene.pfm" "$tmp/results/$capture/disparity.pfm" ||
    fail "disp_maps/$scene.pfm is not $capture's disparity map"
  runtime=$(cat "$tmp/results/hci/runtimes/$scene.txt")
  python3 -c "import sys; sys.exit(not float('$runtime') > 0)" || fail "runtimes/$scene.txt holds '$runtime'"
  badpix=$(python3 -c "import json, sys; print(json.load(open(sys.argv[1]))['all']['badpix_0.07'])" \
    "$tmp/results/$capture/depth_metrics.json") || fail "$capture's HCI scores"
  python3 -c "import sys; sys.exit(not 0 <= $badpix < ${badpix_limit[$scene]})" || fail "$capture: BadPix 0.07 of $badpix %"
  grep -q "HCI BadPix 0.07 %" "$tmp/results/$capture/report.html" || fail "$capture's report does not show its scores"
  echo "HCI scene $scene: disp_maps/$scene.pfm, runtimes/$scene.txt ($runtime s), BadPix 0.07 $badpix %"
done
if [ ! -d "$shared" ]; then
  echo "SKIPPED: the bundled inputs passed; the shared real data was not there to check"
  exit 77
fi
echo PASSED
