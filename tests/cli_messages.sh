#!/usr/bin/env bash
# Error messages say what is wrong and name the option or file (issue: hostile input).
#   bash cli_messages.sh /path/to/pointnpr SCRATCH_DIR
set -uo pipefail
bin=$1
dir=$2/cli_messages
rm -rf "$dir"; mkdir -p "$dir"
. "$(dirname "$0")/lib_cli.sh"
cube_ply "$dir/cube.ply"
has_render=1
built_with_render "$bin" || has_render=0

# camera: the same point, an up along the view; no "non-finite" for finite input
for cmd in render lines; do
  [ $cmd = render ] && [ $has_render = 0 ] && continue
  out=$dir/o.png; [ $cmd = lines ] && out=$dir/o.obj
  "$bin" $cmd "$dir/cube.ply" -o "$out" --eye 1,1,1 --target 1,1,1 --quiet 2> "$dir/e.txt"; rc=$?
  check '[ $rc -eq 2 ] && grep -q "the eye and the target are the same point" "$dir/e.txt" && ! grep -q "non-finite" "$dir/e.txt"' \
        "$cmd: eye == target says so (rc $rc)"
  "$bin" $cmd "$dir/cube.ply" -o "$out" --eye 0,0,5 --target 0,0,0 --up 0,0,3 --quiet 2> "$dir/e.txt"; rc=$?
  check '[ $rc -eq 2 ] && grep -q -- "--up (0,0,3) is parallel to the view direction" "$dir/e.txt"' "$cmd: up along the view names --up (rc $rc)"
done
if [ $has_render = 1 ]; then
  # straight down with the default up (+z) is a plain top view, not an error
  "$bin" render "$dir/cube.ply" -o "$dir/top.png" --eye 0.5,0.5,5 --target 0.5,0.5,0 --size 64x48 --quiet; rc=$?
  check '[ $rc -eq 0 ] && [ -s "$dir/top.png" ]' "a top view with the default up renders (rc $rc)"
fi
# an option whose value overflows the library's float is refused by name
"$bin" features "$dir/cube.ply" -o "$dir/w.ply" --weights 1e308,1e308 2> "$dir/e.txt"; rc=$?
check '[ $rc -eq 2 ] && grep -q -- "--weights wants" "$dir/e.txt"' "--weights 1e308,1e308 names the option (rc $rc)"
# a missing -o says what is missing
"$bin" features "$dir/cube.ply" 2> "$dir/e.txt"; rc=$?
check '[ $rc -eq 2 ] && grep -q "no output given" "$dir/e.txt" && grep -q -- "-o OUT.ply" "$dir/e.txt"' "features without -o says so (rc $rc)"
"$bin" segment 2> "$dir/e.txt"; rc=$?
check '[ $rc -eq 2 ] && grep -q "no input given" "$dir/e.txt"' "segment without input says so (rc $rc)"
if [ $has_render = 1 ]; then
  # lines --svg alone is enough; style names ignore case
  "$bin" lines "$dir/cube.ply" --svg "$dir/alone.svg" --size 160x120 --quiet; rc=$?
  check '[ $rc -eq 0 ] && grep -q "<svg" "$dir/alone.svg"' "lines --svg without -o draws the SVG (rc $rc)"
  "$bin" render "$dir/cube.ply" -o "$dir/s.png" --style Sketchy --size 64x48 --quiet; rc=$?
  check '[ $rc -eq 0 ] && [ -s "$dir/s.png" ]' "--style Sketchy is sketchy (rc $rc)"
fi
# a cloud with no finite point: the camera error names the file
if [ $has_render = 1 ]; then
  printf 'ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\nnan nan nan\ninf 0 0\n' > "$dir/nan.ply"
  "$bin" lines "$dir/nan.ply" -o "$dir/n.obj" --svg "$dir/n.svg" --quiet 2> "$dir/e.txt"; rc=$?
  check '[ $rc -eq 1 ] && grep -q "nan.ply: svg: nothing to draw and no camera" "$dir/e.txt"' "a camera error names the file (rc $rc)"
fi
# the CLI's option table: one message form for every command's out-of-range value and missing
# value, the range as the table holds it
for cmd in features segment; do
  "$bin" $cmd "$dir/cube.ply" -o "$dir/t.ply" --threads 0 2> "$dir/e.txt"; rc=$?
  check '[ $rc -eq 2 ] && grep -q "pointnpr $cmd: --threads wants an integer in 1\.\.[0-9]*, got .0." "$dir/e.txt"' \
        "$cmd --threads 0: the table's message (rc $rc)"
  "$bin" $cmd "$dir/cube.ply" -o "$dir/t.ply" --threads 2> "$dir/e.txt"; rc=$?
  check '[ $rc -eq 2 ] && grep -q "pointnpr $cmd: --threads needs a value (N)" "$dir/e.txt"' "$cmd --threads without a value says so (rc $rc)"
done
"$bin" segment "$dir/cube.ply" -o "$dir/t.ply" --method Components --quiet 2> "$dir/e.txt"; rc=$?
check '[ $rc -eq 0 ]' "segment --method Components: names in any case (rc $rc)"
"$bin" segment "$dir/cube.ply" -o "$dir/t.ply" --method nosuch 2> "$dir/e.txt"; rc=$?
check '[ $rc -eq 2 ] && grep -q "wants jseg, components, rgbgrow or labels, got .nosuch." "$dir/e.txt"' "segment --method nosuch lists the choices (rc $rc)"
"$bin" explain --sketch B --outline On --style SKETCHY > "$dir/o.txt" 2> "$dir/e.txt"; rc=$?
check '[ $rc -eq 0 ] && grep -q "plan for --style SKETCHY" "$dir/o.txt"' "explain: style, sketch and outline in any case (rc $rc)"
"$bin" render "$dir/cube.ply" 2> "$dir/e.txt"; rc=$?
check '[ $rc -eq 2 ] && grep -q "no output given" "$dir/e.txt"' "render without -o says so (rc $rc)"
"$bin" info 2> "$dir/e.txt"; rc=$?
check '[ $rc -eq 2 ] && grep -q "no input given" "$dir/e.txt"' "info without an input says so (rc $rc)"
exit $fail
