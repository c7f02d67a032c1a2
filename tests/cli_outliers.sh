#!/usr/bin/env bash
# Far outliers and unbounded parameters end to end (user reports): a 7x7x7 grid of the unit cube
# plus one point at 1e9 gave 0 feature points, plus one at 1e308 "0 point(s) with finite
# coordinates"; `segment --method components --radius 1e30` on 100k points took 58 s.
#   bash cli_outliers.sh /path/to/pointnpr SCRATCH_DIR
set -euo pipefail
bin=$1
dir=$2/cli_outliers
rm -rf "$dir"; mkdir -p "$dir"
fail=0
check() { if ! eval "$1"; then echo "FAILED: $2" >&2; fail=1; fi; }

# grid.ply: the grid (double coordinates); grid_1e9.ply / grid_1e308.ply: plus (far, 0, 0)
for far in none 1e9 1e308; do
  awk -v far=$far 'BEGIN {
    n = 0
    for (i = 0; i < 7; i++) for (j = 0; j < 7; j++) for (k = 0; k < 7; k++)
      line[n++] = sprintf("%.17g %.17g %.17g", i / 6, j / 6, k / 6)
    if (far != "none") line[n++] = far " 0 0"
    print "ply"; print "format ascii 1.0"; print "element vertex " n
    print "property double x"; print "property double y"; print "property double z"; print "end_header"
    for (q = 0; q < n; q++) print line[q]
  }' > "$dir/grid_$far.ply"
done
feat() { "$bin" features "$dir/$1" -o "$dir/out.ply" "${@:2}" 2>&1 | awk '/^feature points/ {print $3}'; }
clean=$(feat grid_none.ply)
check '[ "$clean" -gt 0 ]' "feature points on the clean grid ($clean)"
check '[ "$(feat grid_1e308.ply)" = "$clean" ]' "1e308 (beyond float range): the grid's $clean feature points"
check '[ "$(feat grid_1e9.ply --drop-outliers)" = "$clean" ]' "1e9 dropped: the grid's $clean feature points"
check '[ "$(feat grid_1e308.ply --drop-outliers)" = "$clean" ]' "1e308 dropped: the grid's $clean feature points"
kept=$(feat grid_1e9.ply)
check '[ $((2 * kept)) -gt "$clean" ]' "1e9 kept: $kept feature points (ties of the lattice; $clean without it, 0 before)"

"$bin" features "$dir/grid_1e308.ply" -o "$dir/out.ply" 2> "$dir/log.txt"
check 'grep -q "1 far outlier(s) (farther than 7.26483 from the robust centre 0.500 0.500 0.500; 1 beyond float range): kept" "$dir/log.txt"' \
      "features says there is a far outlier beyond float range"
check 'grep -q "^points 344 (valid 343)" "$dir/log.txt"' "343 valid points of 344"
"$bin" features "$dir/grid_1e9.ply" -o "$dir/out.ply" --drop-outliers --ascii --quiet
check '[ "$(grep -m1 "element vertex" "$dir/out.ply")" = "element vertex 343" ]' "--drop-outliers writes the 343 grid points"

# too few usable points: the warning counts them right
printf 'ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\nend_header\n0 0 0\n1 0 0\n1e308 0 0\nnan 0 0\n' > "$dir/few.ply"
"$bin" features "$dir/few.ply" -o "$dir/out.ply" --quiet 2> "$dir/few.txt"
check 'grep -q "has 2 point(s) with usable coordinates (of 4: 1 with NaN/Inf coordinates, 1 beyond float range" "$dir/few.txt"' \
      "the warning counts NaN and beyond-float points ($(cat "$dir/few.txt"))"

# info reports them
"$bin" info "$dir/grid_1e9.ply" > "$dir/info.txt"
check 'grep -q "^origin: *0.500 0.500 0.500$" "$dir/info.txt"' "the origin stays at the grid's centre"
check 'grep -q "^outliers: *1 far outlier(s) (farther than 7.26483 " "$dir/info.txt"' "info reports the far outlier"
"$bin" info "$dir/grid_none.ply" > "$dir/info0.txt"
check 'grep -q "^outliers: *0 far outlier(s)" "$dir/info0.txt"' "no far outlier in the clean grid"
"$bin" info "$dir/grid_none.ply" --outlier-factor 1 > "$dir/info1.txt"
check 'grep -q "^outliers: *32 far outlier(s)" "$dir/info1.txt"' "factor 1: the 32 grid points beyond one robust extent (a^2+b^2+c^2 > 19)"

# refused values: usage errors
set +e
for args in "--outlier-factor 0.5" "--outlier-factor 2e6" "--outlier-factor nan"; do
  "$bin" features "$dir/grid_1e9.ply" -o "$dir/x.ply" $args > /dev/null 2>&1; rc=$?
  check '[ $rc -eq 2 ]' "features $args is a usage error (got $rc)"
done
"$bin" features "$dir/grid_1e9.ply" -o "$dir/x.ply" --k 1025 > /dev/null 2>&1; rc=$?
check '[ $rc -eq 2 ]' "features --k 1025 is a usage error (got $rc)"
"$bin" segment "$dir/grid_1e9.ply" -o "$dir/x.ply" --method components --k 257 > /dev/null 2>&1; rc=$?
check '[ $rc -eq 2 ]' "segment --k 257 is a usage error (got $rc)"
set -e

# segment: --drop-outliers, and a radius beyond the diagonal on 20 000 points: one component
"$bin" segment "$dir/grid_1e9.ply" -o "$dir/seg.ply" --method components --drop-outliers --ascii 2> "$dir/seg.txt"
check 'grep -q "^points 343, method components, 1 segments" "$dir/seg.txt"' "segment --drop-outliers: 343 points, one segment"
awk 'BEGIN { srand(3); n = 20000
  print "ply"; print "format ascii 1.0"; print "element vertex " n
  print "property float x"; print "property float y"; print "property float z"; print "end_header"
  for (i = 0; i < n; i++) { c = (i < n / 2) ? 0 : 100; printf "%.6f %.6f %.6f\n", c + rand(), rand(), rand() } }' > "$dir/two.ply"
"$bin" segment "$dir/two.ply" -o "$dir/seg.ply" --method components --radius 1e30 2> "$dir/two.txt"
check 'grep -q "^points 20000, method components, 1 segments" "$dir/two.txt"' "--radius 1e30: one component ($(grep '^points' "$dir/two.txt"))"
"$bin" segment "$dir/two.ply" -o "$dir/seg.ply" --method components --radius 10 2> "$dir/two10.txt"
check 'grep -q "^points 20000, method components, 2 segments" "$dir/two10.txt"' "--radius 10: the two blocks"

if [ $fail -ne 0 ]; then exit 1; fi
echo "cli_outliers: all checks passed"
