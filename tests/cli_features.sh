#!/usr/bin/env bash
# pointnpr features end to end: exact coordinates written back, the promised properties, input
# order kept, usage and error exit codes, degenerate inputs.
#   bash cli_features.sh /path/to/pointnpr SCRATCH_DIR
set -euo pipefail
bin=$1
dir=$2/cli_features
rm -rf "$dir"; mkdir -p "$dir"
fail=0
check() { if ! eval "$1"; then echo "FAILED: $2" >&2; fail=1; fi; }

# A sampled cube 1 x 1 x 1 (spacing 0.05) at a georeferenced offset, double coordinates with
# 17 significant digits, colours and an extra property that must survive.
awk 'BEGIN {
  m = 20; h = 0.05; n = 0
  for (i = 0; i <= m; i++) for (j = 0; j <= m; j++) for (k = 0; k <= m; k++) {
    if (i > 0 && i < m && j > 0 && j < m && k > 0 && k < m) continue
    line[n++] = sprintf("%.17g %.17g %.17g %d %d %d %d", 5123456.789 + i * h, 4012345.678 + j * h, 250.125 + k * h, 200, 100 + i, 50, n)
  }
  print "ply"; print "format ascii 1.0"; print "element vertex " n
  print "property double x"; print "property double y"; print "property double z"
  print "property uchar red"; print "property uchar green"; print "property uchar blue"
  print "property int tag"; print "end_header"
  for (q = 0; q < n; q++) print line[q]
}' > "$dir/cube.ply"
n=$(grep -m1 "element vertex" "$dir/cube.ply" | awk '{print $3}')

"$bin" features "$dir/cube.ply" -o "$dir/out.ply" --ascii 2> "$dir/log.txt"
check 'grep -q "feature points" "$dir/log.txt"' "summary on stderr"
for p in "float nx" "float ny" "float nz" "float feature_degree" "uchar feature_class" \
         "float feature_confidence" "float feature_dir_x" "float feature_dir_y" "float feature_dir_z" \
         "float point_spacing" "int tag" "double x"; do
  check "grep -q \"^property $p\$\" \"$dir/out.ply\"" "output has property $p"
done
# coordinates exactly as they came in, in input order, and the extra property kept
paste <(sed '1,/end_header/d' "$dir/cube.ply" | awk '{print $1, $2, $3, $7}') \
      <(sed '1,/end_header/d' "$dir/out.ply" | awk '{print $1, $2, $3}') > "$dir/pairs.txt"
check '[ "$(wc -l < "$dir/pairs.txt")" -eq "$n" ]' "same number of points ($n)"
check 'awk "{ if (\$1 != \$5 || \$2 != \$6 || \$3 != \$7) { print \"coordinate changed: \" \$0; bad = 1 } } END { exit bad + 0 }" "$dir/pairs.txt"' "coordinates written back exactly"
# the cube has features: directional points on edges, classes within 0..3
cols=$(sed -n '/^element vertex/,/end_header/p' "$dir/out.ply" | grep -c '^property')
classcol=$(sed -n '/^element vertex/,/end_header/p' "$dir/out.ply" | grep '^property' | grep -n 'feature_class' | cut -d: -f1)
dirs=$(sed '1,/end_header/d' "$dir/out.ply" | awk -v c="$classcol" '$c == 2' | wc -l)
bad=$(sed '1,/end_header/d' "$dir/out.ply" | awk -v c="$classcol" -v nc="$cols" 'NF != nc || $c < 0 || $c > 3' | wc -l)
check '[ "$dirs" -gt 100 ]' "directional points found on the cube edges ($dirs)"
check '[ "$bad" -eq 0 ]' "every row has $cols values and a class in 0..3"

# binary output by default, reads back through info
"$bin" features "$dir/cube.ply" -o "$dir/out_bin.ply" --quiet
check 'head -c 200 "$dir/out_bin.ply" | grep -q "binary_little_endian"' "binary output by default"

# usage errors: exit 2
set +e
"$bin" features "$dir/cube.ply" > /dev/null 2>&1; rc=$?
check '[ $rc -eq 2 ]' "missing -o is a usage error (got $rc)"
"$bin" features "$dir/cube.ply" -o "$dir/x.ply" --k 0 > /dev/null 2>&1; rc=$?
check '[ $rc -eq 2 ]' "--k 0 is a usage error (got $rc)"
"$bin" features "$dir/cube.ply" -o "$dir/x.ply" --weights 1 > /dev/null 2>&1; rc=$?
check '[ $rc -eq 2 ]' "--weights 1 is a usage error (got $rc)"
"$bin" features "$dir/cube.ply" -o "$dir/x.ply" --viewpoint 1,2 > /dev/null 2>&1; rc=$?
check '[ $rc -eq 2 ]' "--viewpoint 1,2 is a usage error (got $rc)"
# runtime errors: exit 1 with the file named, no output written
"$bin" features "$dir/missing.ply" -o "$dir/y.ply" 2> "$dir/err.txt"; rc=$?
check '[ $rc -eq 1 ] && grep -q "missing.ply" "$dir/err.txt" && [ ! -e "$dir/y.ply" ]' "missing input: exit 1, named, no output"
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 1\n' > "$dir/trunc.ply"
"$bin" features "$dir/trunc.ply" -o "$dir/y.ply" 2> "$dir/err.txt"; rc=$?
check '[ $rc -eq 1 ] && grep -q "line" "$dir/err.txt" && [ ! -e "$dir/y.ply" ]' "truncated input: exit 1 with the line"
set -e
# degenerate but valid: empty cloud and a single point give a defined output and a warning
printf 'ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n' > "$dir/empty.ply"
"$bin" features "$dir/empty.ply" -o "$dir/empty_out.ply" 2> "$dir/err.txt"
check 'grep -q "warning" "$dir/err.txt" && grep -q "element vertex 0" "$dir/empty_out.ply"' "empty cloud: warning + empty output"
printf 'ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n' > "$dir/one.ply"
"$bin" features "$dir/one.ply" -o "$dir/one_out.ply" --ascii 2> /dev/null
check '[ "$(sed "1,/end_header/d" "$dir/one_out.ply")" = "1 2 3 0 0 0 0 0 0 0 0 0" ]' "one point: zeros"

# --memory-limit: below what the process already holds, refused before the work (exit 1, the
# figures, no output); a large limit runs; a bad size is a usage error
set +e
"$bin" features "$dir/cube.ply" -o "$dir/m.ply" --memory-limit 1K 2> "$dir/err.txt"; rc=$?
check '[ $rc -eq 1 ] && grep -q "needs about .* more, but the limit of 1.0 KiB leaves 0 B" "$dir/err.txt" && [ ! -e "$dir/m.ply" ]' \
  "--memory-limit 1K: exit 1 with the figures, no output (rc $rc)"
"$bin" features "$dir/cube.ply" -o "$dir/m.ply" --memory-limit 64G --quiet; rc=$?
check '[ $rc -eq 0 ] && [ -s "$dir/m.ply" ]' "--memory-limit 64G runs (rc $rc)"
for bad in 0 -5 abc 4X 1e30; do
  "$bin" features "$dir/cube.ply" -o "$dir/m2.ply" --memory-limit "$bad" 2> /dev/null; rc=$?
  check '[ $rc -eq 2 ]' "--memory-limit $bad: usage error (rc $rc)"
done
set -e

if [ $fail -ne 0 ]; then echo "cli_features: FAILED" >&2; exit 1; fi
echo "cli_features: all checks passed"
