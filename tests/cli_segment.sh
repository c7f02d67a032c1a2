#!/usr/bin/env bash
# pointnpr segment end to end: the four methods, the hierarchy cut, the promised properties,
# input order and extra properties kept, usage and error exit codes, degenerate inputs.
#   bash cli_segment.sh /path/to/pointnpr SCRATCH_DIR
set -euo pipefail
bin=$1
dir=$2/cli_segment
rm -rf "$dir"; mkdir -p "$dir"
fail=0
check() { if ! eval "$1"; then echo "FAILED: $2" >&2; fail=1; fi; }

# Two touching planes (x < 1 red, x >= 1 blue), spacing 0.05, with an extra property `part`
# (the truth) and `tag` that must survive.
awk 'BEGIN {
  n = 0
  for (i = 0; i < 40; i++) for (j = 0; j < 20; j++) {
    x = i * 0.05; y = j * 0.05; p = x < 1 ? 0 : 1
    line[n++] = sprintf("%.4f %.4f 0 %d %d %d %d %d", x, y, p ? 30 : 200, 40, p ? 210 : 30, p * 7 + 3, n)
  }
  print "ply"; print "format ascii 1.0"; print "element vertex " n
  print "property float x"; print "property float y"; print "property float z"
  print "property uchar red"; print "property uchar green"; print "property uchar blue"
  print "property int part"; print "property int tag"; print "end_header"
  for (q = 0; q < n; q++) print line[q]
}' > "$dir/planes.ply"

col() { sed -n '/^element vertex/,/end_header/p' "$1" | grep '^property' | grep -n " $2\$" | cut -d: -f1; }
# number of distinct values of property $2 in $1; and the number of (truth, segment) pairs
distinct() { local c; c=$(col "$1" "$2"); sed '1,/end_header/d' "$1" | awk -v c="$c" '{print $c}' | sort -u | wc -l; }
pairs() { local a b; a=$(col "$1" part); b=$(col "$1" segment); sed '1,/end_header/d' "$1" | awk -v a="$a" -v b="$b" '{print $a, $b}' | sort -u | wc -l; }

for m in jseg rgbgrow components; do
  extra=""; [ $m = components ] && extra="--radius 0.06"
  "$bin" segment "$dir/planes.ply" -o "$dir/$m.ply" --method $m $extra --ascii 2> "$dir/$m.log"
  check 'grep -q "segments" "$dir/$m.log"' "$m: summary on stderr"
  for p in "uint segment" "uchar seg_red" "uchar seg_green" "uchar seg_blue" "int part" "int tag" "float x"; do
    check "grep -q \"^property $p\$\" \"$dir/$m.ply\"" "$m: output has property $p"
  done
  check '[ "$(sed "1,/end_header/d" "$dir/$m.ply" | wc -l)" -eq 800 ]' "$m: 800 points"
  tagc=$(col "$dir/$m.ply" tag)
  check "sed '1,/end_header/d' \"$dir/$m.ply\" | awk -v c=$tagc '\$c != NR { bad = 1 } END { exit bad + 0 }'" "$m: input order and tag kept"
done
check '[ "$(distinct "$dir/jseg.ply" segment)" -eq 2 ] && [ "$(pairs "$dir/jseg.ply")" -eq 2 ]' "jseg finds the two planes"
check '[ "$(distinct "$dir/rgbgrow.ply" segment)" -eq 2 ] && [ "$(pairs "$dir/rgbgrow.ply")" -eq 2 ]' "rgbgrow finds the two planes"
check '[ "$(distinct "$dir/components.ply" segment)" -eq 1 ]' "components: the planes touch, one component"
# the segment mean colour of the red plane
rc_=$(col "$dir/jseg.ply" seg_red); pc_=$(col "$dir/jseg.ply" part)
check "sed '1,/end_header/d' \"$dir/jseg.ply\" | awk -v r=$rc_ -v p=$pc_ '(\$p == 3 && \$r != 200) || (\$p == 10 && \$r != 30) { bad = 1 } END { exit bad + 0 }'" "seg_red is the segment mean colour"

# labels from a property; then the hierarchy cut at 1 segment
"$bin" segment "$dir/planes.ply" -o "$dir/labels.ply" --method labels --property part --ascii --quiet
check '[ "$(pairs "$dir/labels.ply")" -eq 2 ] && [ "$(distinct "$dir/labels.ply" segment)" -eq 2 ]' "labels: one segment per part value"
# covariance split: one colour on a folded sheet (z = 0 for x < 1, x = 1 wall above): one jseg
# segment, split at the fold into two pure parts; a flat segment is not split
awk 'BEGIN {
  n = 0
  for (i = 0; i < 20; i++) for (j = 0; j < 20; j++) { line[n++] = sprintf("%.4f %.4f 0 %d", i * 0.05, j * 0.05, 0) }
  for (i = 1; i <= 20; i++) for (j = 0; j < 20; j++) { line[n++] = sprintf("1.0000 %.4f %.4f %d", j * 0.05, i * 0.05, 1) }
  print "ply"; print "format ascii 1.0"; print "element vertex " n
  print "property float x"; print "property float y"; print "property float z"
  print "property uchar red"; print "property uchar green"; print "property uchar blue"
  print "property int part"; print "end_header"
  for (q = 0; q < n; q++) { split(line[q], f, " "); print f[1], f[2], f[3], 120, 120, 120, f[4] }
}' > "$dir/fold.ply"
"$bin" segment "$dir/fold.ply" -o "$dir/fold_split.ply" --split 0.02 --ascii --quiet
check '[ "$(distinct "$dir/fold_split.ply" segment)" -ge 2 ] && [ "$(pairs "$dir/fold_split.ply")" -eq "$(distinct "$dir/fold_split.ply" segment)" ]' "--split cuts the fold into pure parts"
"$bin" segment "$dir/planes.ply" -o "$dir/flat_split.ply" --split 0.02 --ascii --quiet
check '[ "$(distinct "$dir/flat_split.ply" segment)" -eq 2 ]' "--split leaves flat segments whole"
"$bin" segment "$dir/planes.ply" -o "$dir/one.ply" --segments 1 --ascii --quiet
check '[ "$(distinct "$dir/one.ply" segment)" -eq 1 ]' "--segments 1 gives one segment"
"$bin" segment "$dir/planes.ply" -o "$dir/thr.ply" --threshold 0.01 --ascii --quiet
check '[ "$(distinct "$dir/thr.ply" segment)" -eq 2 ]' "--threshold 0.01 keeps the two planes"
# a segmented output read back: labels from its own segment property
"$bin" segment "$dir/jseg.ply" -o "$dir/again.ply" --method labels --ascii --quiet
check '[ "$(distinct "$dir/again.ply" segment)" -eq 2 ]' "labels from the segment property"

# no colours: jseg refuses with a clear message (exit 1), components works
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n' > "$dir/nocol.ply"
set +e
"$bin" segment "$dir/nocol.ply" -o "$dir/x.ply" 2> "$dir/nocol.log"; rc=$?
check '[ $rc -eq 1 ] && grep -q "no colours" "$dir/nocol.log"' "jseg without colours: exit 1 and a message (got $rc)"
"$bin" segment "$dir/nocol.ply" -o "$dir/nc.ply" --method components --quiet; rc=$?
check '[ $rc -eq 0 ]' "components without colours (got $rc)"
"$bin" segment "$dir/nocol.ply" -o "$dir/x.ply" --method labels --property nope 2> /dev/null; rc=$?
check '[ $rc -eq 1 ]' "labels from a missing property: exit 1 (got $rc)"
# empty cloud
printf 'ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n' > "$dir/empty.ply"
"$bin" segment "$dir/empty.ply" -o "$dir/empty_out.ply" --quiet; rc=$?
check '[ $rc -eq 0 ]' "empty cloud (got $rc)"
# usage errors: exit 2
"$bin" segment "$dir/planes.ply" > /dev/null 2>&1; rc=$?
check '[ $rc -eq 2 ]' "missing -o (got $rc)"
"$bin" segment "$dir/planes.ply" -o "$dir/x.ply" --method nope > /dev/null 2>&1; rc=$?
check '[ $rc -eq 2 ]' "unknown method (got $rc)"
"$bin" segment "$dir/planes.ply" -o "$dir/x.ply" --segments 2 --threshold 0.1 > /dev/null 2>&1; rc=$?
check '[ $rc -eq 2 ]' "--segments and --threshold together (got $rc)"
"$bin" segment "$dir/planes.ply" -o "$dir/x.ply" --segments 0 > /dev/null 2>&1; rc=$?
check '[ $rc -eq 2 ]' "--segments 0 (got $rc)"
"$bin" segment "$dir/planes.ply" -o "$dir/x.ply" --split 0.5 > /dev/null 2>&1; rc=$?
check '[ $rc -eq 2 ]' "--split 0.5 (got $rc)"
"$bin" segment "$dir/missing.ply" -o "$dir/x.ply" > /dev/null 2>&1; rc=$?
check '[ $rc -eq 1 ]' "missing input file: exit 1 (got $rc)"
"$bin" segment "$dir/planes.ply" -o "$dir/x.ply" --method components --memory-limit 1K 2> "$dir/mem.log"; rc=$?
check '[ $rc -eq 1 ] && grep -q "planes.ply.*needs about" "$dir/mem.log" && [ ! -e "$dir/x.ply" ]' \
  "a file that does not fit --memory-limit is refused before reading (got $rc)"
set -e
if [ $fail -ne 0 ]; then echo "cli_segment: FAILED" >&2; exit 1; fi
echo "cli_segment: all checks passed"
