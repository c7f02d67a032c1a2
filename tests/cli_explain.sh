#!/usr/bin/env bash
# pointnpr explain: the stage plan per output — what runs, what is skipped, what is reused.
#   bash cli_explain.sh /path/to/pointnpr SCRATCH_DIR
set -euo pipefail
bin=$1
dir=$2/cli_explain
rm -rf "$dir"; mkdir -p "$dir"
fail=0
expect() { # expect "<args>" "<stage>" run|skip
  local out
  out=$("$bin" explain $1)
  if ! grep -Eq "^  $2 +$3 " <<< "$out"; then echo "FAILED: explain $1: $2 should be '$3'" >&2; echo "$out" >&2; fail=1; fi
}
expect "--style points" "kd-tree \+ knn" skip
expect "--style points" "classify" skip
expect "--style sketchy --sketch a" "classify" run
expect "--style sketchy --sketch a" "dither" skip
expect "--style sketchy --sketch c" "dither" run
expect "--style sketchy" "orient" skip  # the tone's key light is two-sided: no orientation
expect "--style sketchy --outline on" "normals \(PCA\)" run   # outlines weigh depth jumps by the normals
expect "--style lines" "orient" skip
expect "--style cartoon" "normals \(PCA\)" run
expect "--style cartoon --outline off" "kd-tree \+ knn" skip  # colours assumed: JSEG only
expect "--style stipple" "dither" run
expect "--style painterly" "feature degree" run
expect "--style painterly" "dither" skip
expect "--style cartoon" "segments" run
expect "--style cartoon" "feature degree" skip
expect "--style lines" "profile lines" run
expect "--style brush" "brush sizes" run
expect "--style brush" "kd-tree \+ knn" skip   # the brush stage has its own neighbourhoods
expect "--style points" "brush sizes" skip
expect "--style hierarchy" "sphere hierarchy" run
expect "--style hierarchy" "kd-tree \+ knn" skip   # the tree finds its own neighbourhoods
expect "--style brush" "sphere hierarchy" skip
expect "--style lines" "dither" skip
expect "--segment components" "classify" skip
expect "--features" "orient" run
# an input that carries the features: everything reused, nothing recomputed
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty float feature_degree\nproperty uchar feature_class\nproperty float feature_dir_x\nproperty float feature_dir_y\nproperty float feature_dir_z\nend_header\n0 0 0 0 0 0 0 0\n1 0 0 0 0 0 0 0\n0 1 0 0 0 0 0 0\n' > "$dir/f.ply"
expect "$dir/f.ply --style sketchy" "classify" skip
expect "$dir/f.ply --style sketchy --outline on" "normals \(PCA\)" run   # the outlines want normals f.ply lacks
expect "$dir/f.ply --style sketchy" "kd-tree \+ knn" skip
expect "$dir/f.ply --style points" "normals \(PCA\)" run    # colourless: shaded from normals
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n0 0 0 1 2 3\n1 0 0 1 2 3\n0 1 0 1 2 3\n' > "$dir/c.ply"
expect "$dir/c.ply --style sketchy" "orient" skip
expect "$dir/c.ply --style sketchy" "dither" run
set +e
"$bin" explain --style oil > /dev/null 2>&1; rc=$?
[ $rc -eq 2 ] || { echo "FAILED: unknown style must exit 2 (got $rc)" >&2; fail=1; }
set -e
if [ $fail -ne 0 ]; then echo "cli_explain: FAILED" >&2; exit 1; fi
echo "cli_explain: all checks passed"
