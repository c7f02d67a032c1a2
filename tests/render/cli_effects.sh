#!/usr/bin/env bash
# pointnpr render --effects end to end: a two-segment scene through a pipeline file (one layer per
# node, PNG of the asked size, deterministic), an empty pipeline equal to the plain frame, and the
# errors: a bad pipeline line (FILE:LINE, exit 2, nothing written), --effects with a vector
# output, --layering without --effects, --effects with --style-map.
#   bash cli_effects.sh /path/to/pointnpr SCRATCH_DIR        (exit 77: no headless GL here)
set -uo pipefail
bin=$1
dir=$2/cli_effects
rm -rf "$dir"; mkdir -p "$dir"
source "$(dirname "$0")/../lib_cli.sh" # check, fail
png_w() { od -An -tu1 -j16 -N4 "$1" | awk '{print $1*16777216+$2*65536+$3*256+$4}'; }
png_h() { od -An -tu1 -j20 -N4 "$1" | awk '{print $1*16777216+$2*65536+$3*256+$4}'; }

# a back plane (segment 2, blue) and a square in front of it (segment 1, red)
awk 'BEGIN {
  n = 0
  for (i = 0; i <= 40; i++) for (j = 0; j <= 40; j++) line[n++] = sprintf("%g %g 0 60 90 200 2", i * 0.05, j * 0.05)
  for (i = 0; i <= 12; i++) for (j = 0; j <= 12; j++) line[n++] = sprintf("%g %g 0.4 210 50 40 1", 0.7 + i * 0.05, 0.7 + j * 0.05)
  print "ply"; print "format ascii 1.0"; print "element vertex " n
  print "property float x"; print "property float y"; print "property float z"
  print "property uchar red"; print "property uchar green"; print "property uchar blue"
  print "property uint segment"; print "end_header"
  for (q = 0; q < n; q++) print line[q]
}' > "$dir/scene.ply"

"$bin" render "$dir/scene.ply" -o "$dir/plain.png" --size 160x120 2> "$dir/log.txt"; rc=$?
if [ $rc -ne 0 ] && grep -q "headless OpenGL" "$dir/log.txt"; then
  echo "cli_effects: skipped: $(cat "$dir/log.txt")" >&2
  exit 77
fi
check '[ $rc -eq 0 ]' "plain render ($(cat "$dir/log.txt"))"

printf '# nothing\n' > "$dir/empty.fx"
"$bin" render "$dir/scene.ply" -o "$dir/empty.png" --size 160x120 --effects "$dir/empty.fx" 2> "$dir/log.txt"; rc=$?
check '[ $rc -eq 0 ] && cmp -s "$dir/plain.png" "$dir/empty.png"' "an empty pipeline is the plain frame ($(cat "$dir/log.txt"))"

cat > "$dir/two.fx" <<'FX'
layering inpainted
node front labels 1
toon levels=4
node back labels 2
watercolour
FX
"$bin" render "$dir/scene.ply" -o "$dir/two.png" --size 160x120 --effects "$dir/two.fx" 2> "$dir/log.txt"; rc=$?
check '[ $rc -eq 0 ]' "two nodes render ($(cat "$dir/log.txt"))"
check 'grep -q "effects: 2 layers" "$dir/log.txt"' "one layer per node: $(grep layers "$dir/log.txt")"
check '[ "$(png_w "$dir/two.png")" -eq 160 ] && [ "$(png_h "$dir/two.png")" -eq 120 ]' "PNG is 160x120"
check '! cmp -s "$dir/two.png" "$dir/plain.png"' "the effects change the picture"
"$bin" render "$dir/scene.ply" -o "$dir/two_again.png" --size 160x120 --effects "$dir/two.fx" --quiet; rc=$?
check 'cmp -s "$dir/two.png" "$dir/two_again.png"' "deterministic"
"$bin" render "$dir/scene.ply" -o "$dir/fragment.png" --size 160x120 --effects "$dir/two.fx" --layering fragment --quiet; rc=$?
check '[ $rc -eq 0 ] && ! cmp -s "$dir/two.png" "$dir/fragment.png"' "--layering fragment differs from inpainted"

printf 'node a labels 1\ntoon levels=99\n' > "$dir/bad.fx"
"$bin" render "$dir/scene.ply" -o "$dir/bad.png" --effects "$dir/bad.fx" 2> "$dir/log.txt"; rc=$?
check '[ $rc -eq 2 ]' "a bad pipeline line exits 2 (got $rc)"
check 'grep -q "bad.fx:2:" "$dir/log.txt" && grep -q "levels" "$dir/log.txt"' "FILE:LINE names the parameter: $(cat "$dir/log.txt")"
check '[ ! -e "$dir/bad.png" ]' "nothing written"
"$bin" render "$dir/scene.ply" -o "$dir/x.svg" --effects "$dir/two.fx" 2> "$dir/log.txt"; rc=$?
check '[ $rc -eq 2 ] && grep -q "must be a PNG" "$dir/log.txt"' "--effects with an SVG: $(cat "$dir/log.txt")"
"$bin" render "$dir/scene.ply" -o "$dir/x.png" --layering none 2> "$dir/log.txt"; rc=$?
check '[ $rc -eq 2 ] && grep -q "is for --effects" "$dir/log.txt"' "--layering alone: $(cat "$dir/log.txt")"
"$bin" render "$dir/scene.ply" -o "$dir/x.png" --effects-scale 0.5 2> "$dir/log.txt"; rc=$?
check '[ $rc -eq 2 ] && grep -q -- "--effects-scale is for --effects" "$dir/log.txt"' "--effects-scale alone: $(cat "$dir/log.txt")"
"$bin" render "$dir/scene.ply" -o "$dir/x.png" --effects "$dir/two.fx" --effects-scale 0.01 2> "$dir/log.txt"; rc=$?
check '[ $rc -eq 2 ] && grep -q "0.0625..1" "$dir/log.txt"' "--effects-scale out of range: $(cat "$dir/log.txt")"
"$bin" render "$dir/scene.ply" -o "$dir/half.png" --size 200x150 --effects "$dir/two.fx" --effects-scale 0.5 2> "$dir/log.txt"; rc=$?
check '[ $rc -eq 0 ] && grep -q "2 layers of 100x75" "$dir/log.txt" && [ -s "$dir/half.png" ]' "a preview draws half-size layers into the full image: $(grep layers "$dir/log.txt")"
printf '1 sketchy\n' > "$dir/map.txt"
"$bin" render "$dir/scene.ply" -o "$dir/x.png" --effects "$dir/two.fx" --style-map "$dir/map.txt" 2> "$dir/log.txt"; rc=$?
check '[ $rc -eq 2 ] && grep -q "give one" "$dir/log.txt"' "--effects with --style-map: $(cat "$dir/log.txt")"
"$bin" render "$dir/scene.ply" -o "$dir/x.png" --effects "$dir/missing.fx" 2> "$dir/log.txt"; rc=$?
check '[ $rc -eq 2 ] && grep -q "missing.fx" "$dir/log.txt"' "a missing file is named: $(cat "$dir/log.txt")"
check '[ ! -e "$dir/x.png" ]' "nothing written on errors"
exit $fail
