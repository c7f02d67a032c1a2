#!/usr/bin/env bash
# pointnpr lines end to end: a cube's lines as OBJ, PLY and SVG; features computed on the fly;
# no directional points; usage and runtime errors.
#   bash cli_lines.sh /path/to/pointnpr SCRATCH_DIR
set -euo pipefail
bin=$1
dir=$2/cli_lines
rm -rf "$dir"; mkdir -p "$dir"
fail=0
check() { if ! eval "$1"; then echo "FAILED: $2" >&2; fail=1; fi; }

# a cube 1 x 1 x 1 sampled every 0.025, at a georeferenced offset, no features in the file
awk 'BEGIN {
  m = 40; h = 0.025; n = 0
  for (i = 0; i <= m; i++) for (j = 0; j <= m; j++) for (k = 0; k <= m; k++) {
    if (i > 0 && i < m && j > 0 && j < m && k > 0 && k < m) continue
    line[n++] = sprintf("%.17g %.17g %.17g", 5000000 + i * h, 4000000 + j * h, 100 + k * h)
  }
  print "ply"; print "format ascii 1.0"; print "element vertex " n
  print "property double x"; print "property double y"; print "property double z"; print "end_header"
  for (q = 0; q < n; q++) print line[q]
}' > "$dir/cube.ply"

"$bin" lines "$dir/cube.ply" -o "$dir/cube.obj" --svg "$dir/cube.svg" 2> "$dir/log.txt"
check 'grep -q "computing them" "$dir/log.txt"' "features computed when missing"
nl=$(grep -c '^l ' "$dir/cube.obj" || true)
check '[ "$nl" -ge 12 ] && [ "$nl" -le 16 ]' "12 edges give 12..16 polylines in OBJ (got $nl)"
# every OBJ vertex lies on an edge of the cube (world coordinates, offset kept)
bad=$(awk '/^v / { x = $2 - 5000000; y = $3 - 4000000; z = $4 - 100
  n = 0; if (x < 0.05 || x > 0.95) n++; if (y < 0.05 || y > 0.95) n++; if (z < 0.05 || z > 0.95) n++
  if (n < 2) c++ } END { print c + 0 }' "$dir/cube.obj")
check '[ "$bad" -eq 0 ]' "every line vertex near a cube edge ($bad off)"
check 'grep -q "<svg" "$dir/cube.svg" && grep -q "<polyline" "$dir/cube.svg"' "SVG written with polylines"
"$bin" lines "$dir/cube.ply" -o "$dir/cube_lines.ply" --quiet --taper 0.3 --outline off --svg "$dir/cube_taper.svg"
check 'grep -q "^element edge" "$dir/cube_lines.ply"' "PLY polylines have an edge element"
check 'grep -q "<path" "$dir/cube_taper.svg"' "tapered strokes are filled outlines"

# a plane: no directional points, an empty result and a message, exit 0
awk 'BEGIN { print "ply"; print "format ascii 1.0"; print "element vertex 400"
  print "property float x"; print "property float y"; print "property float z"; print "end_header"
  for (i = 0; i < 20; i++) for (j = 0; j < 20; j++) print i * 0.1, j * 0.1, 0 }' > "$dir/plane.ply"
"$bin" lines "$dir/plane.ply" -o "$dir/plane.obj" 2> "$dir/log2.txt"
check 'grep -q "no directional" "$dir/log2.txt" && [ "$(grep -c "^l " "$dir/plane.obj" || true)" -eq 0 ]' "plane: no lines, a message"

set +e
"$bin" lines "$dir/cube.ply" -o "$dir/x.txt" > /dev/null 2>&1; rc=$?
check '[ $rc -eq 2 ]' "unknown output extension is a usage error (got $rc)"
"$bin" lines "$dir/cube.ply" -o "$dir/x.obj" --taper 2 > /dev/null 2>&1; rc=$?
check '[ $rc -eq 2 ]' "--taper 2 is a usage error (got $rc)"
"$bin" lines "$dir/cube.ply" -o "$dir/x.obj" --eye 1,2,3 > /dev/null 2>&1; rc=$?
check '[ $rc -eq 2 ]' "--eye without --target is a usage error (got $rc)"
"$bin" lines "$dir/missing.ply" -o "$dir/y.obj" 2> "$dir/err.txt"; rc=$?
check '[ $rc -eq 1 ] && grep -q missing.ply "$dir/err.txt" && [ ! -e "$dir/y.obj" ]' "missing input: exit 1, named, no output"
# --threads: the same lines with one thread and with three
"$bin" lines "$dir/cube.ply" -o "$dir/t1.obj" --threads 1 --quiet; rc1=$?
"$bin" lines "$dir/cube.ply" -o "$dir/t3.obj" --threads 3 --quiet; rc3=$?
check '[ $rc1 -eq 0 ] && [ $rc3 -eq 0 ] && [ "$(grep -c "^l " "$dir/t1.obj")" -gt 0 ] && cmp -s "$dir/t1.obj" "$dir/t3.obj"' "--threads 1 and 3 write the same lines"
"$bin" lines "$dir/cube.ply" -o "$dir/t0.obj" --threads 0 > /dev/null 2>&1; rc=$?
check '[ $rc -eq 2 ] && [ ! -e "$dir/t0.obj" ]' "--threads 0 refused (usage)"
set -e

if [ $fail -ne 0 ]; then echo "cli_lines: FAILED" >&2; exit 1; fi
echo "cli_lines: all checks passed"
