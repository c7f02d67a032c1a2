#!/usr/bin/env bash
# pointnpr animate IN --save-path FILE without -o: the camera path only, in every build (camera
# paths are the core library's; the renderer is not needed): an orbit is a loop of 181 keys, a
# flyover an open path, a path file read and written back is the same file, the path does not
# depend on render-only options, the camera of --camera FILE starts the preset; usage errors
# exit 2. (tests/render/cli_animate.sh checks that it equals the path of a rendered animation.)
#   bash cli_animate_path.sh /path/to/pointnpr SCRATCH_DIR
set -uo pipefail
bin=$1
dir=$2/cli_animate_path
rm -rf "$dir"; mkdir -p "$dir"
fail=0
check() { if ! eval "$1"; then echo "FAILED: $2" >&2; fail=1; fi; }

# a box 1 x 0.6 x 0.4 sampled every 0.05 on its faces, at a georeferenced offset
awk 'BEGIN {
  n = 0
  for (i = 0; i <= 20; i++) for (j = 0; j <= 12; j++) for (k = 0; k <= 8; k++) {
    if (i > 0 && i < 20 && j > 0 && j < 12 && k > 0 && k < 8) continue
    line[n++] = sprintf("%.17g %.17g %.17g", 5123456.789 + i * 0.05, 4012345.678 + j * 0.05, 250.125 + k * 0.05)
  }
  print "ply"; print "format ascii 1.0"; print "element vertex " n
  print "property double x"; print "property double y"; print "property double z"; print "end_header"
  for (q = 0; q < n; q++) print line[q]
}' > "$dir/box.ply"

"$bin" animate "$dir/box.ply" --orbit --duration 2 --save-path "$dir/orbit.campath" --size 160x120 2> "$dir/log.txt"
rc=$?
check '[ $rc -eq 0 ] && grep -q "wrote $dir/orbit.campath" "$dir/log.txt"' "orbit path written (rc $rc: $(cat "$dir/log.txt"))"
check 'grep -q "^loop$" "$dir/orbit.campath" && [ "$(grep -c "^time " "$dir/orbit.campath")" -eq 181 ]' "an orbit is a loop of 181 keys"
check '[ -z "$(ls "$dir" | grep -v -e "^box.ply$" -e "^orbit.campath$" -e "^log.txt$")" ]' "nothing else is written"
"$bin" animate "$dir/box.ply" --orbit --duration 2 --save-path "$dir/orbit2.campath" --size 160x120 --style sketchy --seed 7 --quiet
check '[ $? -eq 0 ] && cmp -s "$dir/orbit.campath" "$dir/orbit2.campath"' "render-only options do not change the path"
"$bin" animate "$dir/box.ply" --flyover --duration 3 --save-path "$dir/fly.campath" --quiet
check '[ $? -eq 0 ] && ! grep -q "^loop$" "$dir/fly.campath" && [ "$(grep -c "^time " "$dir/fly.campath")" -gt 1 ]' "a flyover is an open path"
"$bin" animate "$dir/box.ply" --camera-path "$dir/orbit.campath" --save-path "$dir/copy.campath" --quiet
check '[ $? -eq 0 ] && cmp -s "$dir/orbit.campath" "$dir/copy.campath"' "a path file written back is the same file"
printf 'eye 5123460 4012340 260\ntarget 5123457.289 4012345.978 250.325\nup 0 0 1\nfov 30\n' > "$dir/start.cam"
"$bin" animate "$dir/box.ply" --orbit --degrees 90 --camera "$dir/start.cam" --save-path "$dir/q.campath" --quiet
check '[ $? -eq 0 ] && ! grep -q "^loop$" "$dir/q.campath" && [ "$(awk "/^eye/ { print; exit }" "$dir/q.campath")" = "eye 5123460 4012340 260" ] && grep -q "^fov 30$" "$dir/q.campath"' \
  "a quarter orbit starts at --camera FILE's camera"

# usage errors: 2
for args in "$dir/box.ply --orbit" "$dir/box.ply --save-path $dir/u.campath" "--orbit --save-path $dir/u.campath" \
            "$dir/box.ply --orbit --flyover --save-path $dir/u.campath" "$dir/box.ply --flyover --degrees 90 --save-path $dir/u.campath"; do
  "$bin" animate $args > /dev/null 2>&1
  rc=$?
  check '[ $rc -eq 2 ]' "usage error exits 2: animate $args (got $rc)"
done
check '[ ! -e "$dir/u.campath" ]' "no path written on a usage error"
# the input is never overwritten
cp "$dir/box.ply" "$dir/keep.ply"
"$bin" animate "$dir/box.ply" --orbit --save-path "$dir/box.ply" 2> "$dir/e.txt"; rc=$?
check '[ $rc -eq 1 ] && grep -q "is the input" "$dir/e.txt" && cmp -s "$dir/box.ply" "$dir/keep.ply"' "--save-path IN is refused (rc $rc: $(cat "$dir/e.txt"))"
exit $fail
