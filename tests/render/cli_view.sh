#!/usr/bin/env bash
# The default camera from the command line (docs/view.md): `pointnpr render` of a y-up PLY
# without camera options looks from above the floor (the camera it writes with --save-camera);
# --up y, --up 0,1,0 and --up auto give that same camera, --up -y looks from below, --up with
# --eye/--target takes both forms, a bad --up exits 2 naming --up.
#   bash cli_view.sh /path/to/pointnpr SCRATCH_DIR        (exit 77: no headless GL here)
set -uo pipefail
bin=$1
dir=$2/cli_view
rm -rf "$dir"; mkdir -p "$dir"
fail=0
check() { if ! eval "$1"; then echo "FAILED: $2" >&2; fail=1; fi; }
# field N (2..4) of the "eye" / "target" / "up" line of a camera file
cam() { awk -v k="$2" -v f="$3" '$1 == k { print $f }' "$1"; }

# y up: a floor 20 x 20 at y = 0 (x, z in -10..10) and a box 4 x 3 x 4 standing on it
awk 'BEGIN {
  n = 0; h = 0.25
  for (i = 0; i <= 80; i++) for (k = 0; k <= 80; k++) line[n++] = sprintf("%g 0 %g", -10 + i * h, -10 + k * h)
  for (i = 0; i <= 16; i++) for (k = 0; k <= 16; k++) line[n++] = sprintf("%g 3 %g", i * h, k * h)
  for (j = 1; j < 12; j++) for (i = 0; i <= 16; i++) {
    line[n++] = sprintf("%g %g 0", i * h, j * h); line[n++] = sprintf("%g %g 4", i * h, j * h)
    line[n++] = sprintf("0 %g %g", j * h, i * h); line[n++] = sprintf("4 %g %g", j * h, i * h)
  }
  print "ply"; print "format ascii 1.0"; print "element vertex " n
  print "property float x"; print "property float y"; print "property float z"; print "end_header"
  for (q = 0; q < n; q++) print line[q]
}' > "$dir/yup.ply"

"$bin" render "$dir/yup.ply" -o "$dir/auto.png" --size 160x120 --save-camera "$dir/auto.cam" --quiet 2> "$dir/log.txt"
rc=$?
if [ $rc -ne 0 ] && grep -q "headless OpenGL" "$dir/log.txt"; then
  echo "cli_view: skipped: $(cat "$dir/log.txt")" >&2
  exit 77
fi
check '[ $rc -eq 0 ]' "default render exits 0 ($(cat "$dir/log.txt"))"
eye_y=$(cam "$dir/auto.cam" eye 3); target_y=$(cam "$dir/auto.cam" target 3)
echo "default camera: eye y $eye_y, target y $target_y, up $(cam "$dir/auto.cam" up 2) $(cam "$dir/auto.cam" up 3) $(cam "$dir/auto.cam" up 4)"
check 'awk -v e="$eye_y" -v t="$target_y" "BEGIN { exit !(e > 5 && e > t) }"' "eye above the floor and looking down (eye y $eye_y, target y $target_y)"
check '[ "$(cam "$dir/auto.cam" up 2) $(cam "$dir/auto.cam" up 3) $(cam "$dir/auto.cam" up 4)" = "0 1 0" ]' "up is +y"

# both forms of --up, and auto, give the same default camera; -y looks from below
for u in y 0,1,0 auto; do
  "$bin" render "$dir/yup.ply" -o "$dir/up.png" --size 160x120 --up "$u" --save-camera "$dir/up_$u.cam" --quiet
  check '[ $? -eq 0 ] && cmp -s "$dir/up_$u.cam" "$dir/auto.cam"' "--up $u gives the default camera"
done
"$bin" render "$dir/yup.ply" -o "$dir/down.png" --size 160x120 --up -y --save-camera "$dir/down.cam" --quiet
check 'awk -v e="$(cam "$dir/down.cam" eye 3)" "BEGIN { exit !(e < 0) }"' "--up -y looks from below the floor"

# with --eye/--target: the axis form and the vector form
"$bin" render "$dir/yup.ply" -o "$dir/e.png" --size 160x120 --eye 20,15,20 --target 0,0,0 --up y --save-camera "$dir/e1.cam" --quiet
check '[ $? -eq 0 ] && [ "$(cam "$dir/e1.cam" up 2) $(cam "$dir/e1.cam" up 3) $(cam "$dir/e1.cam" up 4)" = "0 1 0" ]' "--eye/--target with --up y"
"$bin" render "$dir/yup.ply" -o "$dir/e.png" --size 160x120 --eye 20,15,20 --target 0,0,0 --up 0,1,0 --save-camera "$dir/e2.cam" --quiet
check '[ $? -eq 0 ] && cmp -s "$dir/e1.cam" "$dir/e2.cam"' "--eye/--target with --up 0,1,0"

# bad values: exit 2 with a message naming --up (render and lines)
for u in w 0,0,0 1,2; do
  "$bin" render "$dir/yup.ply" -o "$dir/bad.png" --up "$u" 2> "$dir/bad.txt"
  check '[ $? -eq 2 ] && grep -q -- "--up" "$dir/bad.txt"' "render --up $u exits 2 naming --up"
done
"$bin" lines "$dir/yup.ply" -o "$dir/bad.obj" --up w 2> "$dir/bad.txt"
check '[ $? -eq 2 ] && grep -q -- "--up" "$dir/bad.txt"' "lines --up w exits 2 naming --up"

exit $fail
