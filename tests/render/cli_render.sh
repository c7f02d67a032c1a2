#!/usr/bin/env bash
# pointnpr render end to end: PNG output (size, RGB / RGBA), the camera and budget options,
# features computed on the fly for sketchy, exit codes for usage and runtime errors.
#   bash cli_render.sh /path/to/pointnpr SCRATCH_DIR        (exit 77: no headless GL here)
set -uo pipefail
bin=$1
dir=$2/cli_render
rm -rf "$dir"; mkdir -p "$dir"
fail=0
check() { if ! eval "$1"; then echo "FAILED: $2" >&2; fail=1; fi; }
# PNG header: width, height (big endian at bytes 16..23), colour type at byte 25 (2 RGB, 6 RGBA)
png_w() { od -An -tu1 -j16 -N4 "$1" | awk '{print $1*16777216+$2*65536+$3*256+$4}'; }
png_h() { od -An -tu1 -j20 -N4 "$1" | awk '{print $1*16777216+$2*65536+$3*256+$4}'; }
png_type() { od -An -tu1 -j25 -N1 "$1" | tr -d ' '; }

# a sampled cube (spacing 0.05) at a georeferenced offset, coloured
awk 'BEGIN {
  m = 20; h = 0.05; n = 0
  for (i = 0; i <= m; i++) for (j = 0; j <= m; j++) for (k = 0; k <= m; k++) {
    if (i > 0 && i < m && j > 0 && j < m && k > 0 && k < m) continue
    line[n++] = sprintf("%.17g %.17g %.17g %d %d %d", 5123456.789 + i * h, 4012345.678 + j * h, 250.125 + k * h, 200, 100 + i * 5, 50)
  }
  print "ply"; print "format ascii 1.0"; print "element vertex " n
  print "property double x"; print "property double y"; print "property double z"
  print "property uchar red"; print "property uchar green"; print "property uchar blue"
  print "end_header"
  for (q = 0; q < n; q++) print line[q]
}' > "$dir/cube.ply"

"$bin" render "$dir/cube.ply" -o "$dir/points.png" --size 200x150 2> "$dir/log.txt"
rc=$?
if [ $rc -ne 0 ] && grep -q "headless OpenGL" "$dir/log.txt"; then
  echo "cli_render: skipped: $(cat "$dir/log.txt")" >&2
  exit 77
fi
check '[ $rc -eq 0 ]' "points render exits 0 ($(cat "$dir/log.txt"))"
check '[ "$(head -c 8 "$dir/points.png" | od -An -tx1 | tr -d " ")" = "89504e470d0a1a0a" ]' "PNG signature"
check '[ "$(png_w "$dir/points.png")" -eq 200 ] && [ "$(png_h "$dir/points.png")" -eq 150 ]' "PNG is 200x150"
check '[ "$(png_type "$dir/points.png")" -eq 2 ]' "PNG is RGB without --alpha"
check 'grep -q "points drawn" "$dir/log.txt"' "summary on stderr"

# sketchy on a cloud without features: computed on the fly
"$bin" render "$dir/cube.ply" -o "$dir/sketchy.png" --style sketchy --sketch b --size 160x120 --alpha 2> "$dir/log2.txt"
rc=$?; check '[ $rc -eq 0 ]' "sketchy render exits 0 ($(cat "$dir/log2.txt"))"
check 'grep -q "computing features" "$dir/log2.txt"' "features computed for sketchy"
check '[ "$(png_type "$dir/sketchy.png")" -eq 6 ]' "PNG is RGBA with --alpha"

# lines on a cloud without features: features and profile lines computed on the fly
"$bin" render "$dir/cube.ply" -o "$dir/lines.png" --style lines --line-width 3 --faint 0.3 --size 160x120 2> "$dir/log3.txt"
rc=$?; check '[ $rc -eq 0 ]' "lines render exits 0 ($(cat "$dir/log3.txt"))"
check 'grep -q "profile lines" "$dir/log3.txt" && grep -q "style lines" "$dir/log3.txt"' "profile lines computed for lines"

"$bin" render "$dir/cube.ply" -o "$dir/stipple.png" --style stipple --dot-size 2 --size 160x120 --quiet
check '[ $? -eq 0 ] && [ "$(png_w "$dir/stipple.png")" -eq 160 ]' "stipple render exits 0"

"$bin" render "$dir/cube.ply" -o "$dir/cartoon.png" --style cartoon --levels 3 --outline-scale 2.5 --size 160x120 --quiet
check '[ $? -eq 0 ] && [ "$(png_w "$dir/cartoon.png")" -eq 160 ]' "cartoon render exits 0"

# explicit camera in world coordinates, budget, seed: deterministic
for k in 1 2; do
  "$bin" render "$dir/cube.ply" -o "$dir/cam$k.png" --size 120x90 --quiet --eye 5123459,4012342,252 \
    --target 5123457.289,4012346.178,250.625 --up 0,0,1 --fov 50 --budget 2000 --seed 7 --background 0,0,64
  check '[ $? -eq 0 ]' "camera render $k exits 0"
done
check 'cmp -s "$dir/cam1.png" "$dir/cam2.png"' "same input and seed give identical PNGs"

# the screen-space budget: by default at most 2 points per covered pixel (a 24x18 frame: at most
# 864 of the cube's points), --budget all draws every point, --density -1 too
"$bin" render "$dir/cube.ply" -o "$dir/small.png" --size 24x18 2> "$dir/small.txt"
rc=$?; drawn=$(sed -n 's/.*: \([0-9]*\) of \([0-9]*\) points drawn.*/\1 \2/p' "$dir/small.txt")
check '[ $rc -eq 0 ] && [ "${drawn% *}" -le 864 ] && [ "${drawn% *}" -lt "${drawn#* }" ]' "default density: $drawn drawn"
for all in "--budget all" "--density -1"; do
  "$bin" render "$dir/cube.ply" -o "$dir/small.png" --size 24x18 $all 2> "$dir/small.txt"
  rc=$?; drawn=$(sed -n 's/.*: \([0-9]*\) of \([0-9]*\) points drawn.*/\1 \2/p' "$dir/small.txt")
  check '[ $rc -eq 0 ] && [ "${drawn% *}" = "${drawn#* }" ]' "$all: every point drawn ($drawn)"
done
"$bin" render "$dir/cube.ply" -o "$dir/x.png" --budget all --density 0.5 2> "$dir/err.txt"
rc=$?; check '[ $rc -eq 2 ] && grep -q "give one" "$dir/err.txt"' "--budget all with --density exits 2 (got $rc)"

# --memory-limit: the estimate of what is left (features, upload, frame) must fit
"$bin" render "$dir/cube.ply" -o "$dir/mem.png" --style sketchy --memory-limit 1K 2> "$dir/err.txt"
rc=$?; check '[ $rc -eq 1 ] && grep -q "needs about" "$dir/err.txt" && [ ! -e "$dir/mem.png" ]' "--memory-limit 1K: exit 1, no output (rc $rc)"
"$bin" render "$dir/cube.ply" -o "$dir/mem.png" --style sketchy --size 64x48 --memory-limit 64G --quiet
rc=$?; check '[ $rc -eq 0 ] && [ -s "$dir/mem.png" ]' "--memory-limit 64G renders (rc $rc)"

# usage errors: 2
for args in "" "$dir/cube.ply" "$dir/cube.ply -o $dir/x.png --style oil" "$dir/cube.ply -o $dir/x.png --size 0x10" \
            "$dir/cube.ply -o $dir/x.png --eye 1,2,3" "$dir/cube.ply -o $dir/x.png --background 300,0,0" \
            "$dir/cube.ply -o $dir/x.png --budget -5" "$dir/cube.ply -o $dir/x.png --budget al" "$dir/cube.ply -o $dir/x.png --memory-limit 0" "$dir/cube.ply -o $dir/x.png --sketch d" "$dir/cube.ply -o $dir/x.png --bogus" \
            "$dir/cube.ply -o $dir/x.png --style lines --faint 2" "$dir/cube.ply -o $dir/x.png --line-width 0" \
            "$dir/cube.ply -o $dir/x.png --style stipple --dot-size -1" \
            "$dir/cube.ply -o $dir/x.png --style cartoon --levels 1" "$dir/cube.ply -o $dir/x.png --outline-scale 0.5"; do
  "$bin" render $args > /dev/null 2>&1
  rc=$?
  check '[ $rc -eq 2 ]' "usage error exits 2: render $args (got $rc)"
done
# runtime errors: 1 with a message
"$bin" render "$dir/missing.ply" -o "$dir/x.png" 2> "$dir/err.txt"
check '[ $? -eq 1 ] && grep -q "pointnpr render:" "$dir/err.txt"' "missing input exits 1 with a message"
"$bin" render "$dir/cube.ply" -o "$dir/no-such-dir/x.png" --quiet 2> "$dir/err2.txt"
check '[ $? -eq 1 ] && grep -q "cannot write into the folder" "$dir/err2.txt"' "unwritable output exits 1 with a message"
"$bin" render "$dir/cube.ply" -o "$dir/x.png" --quiet --eye 1,1,1 --target 1,1,1 2> "$dir/err3.txt"
check '[ $? -eq 2 ] && grep -q "same point" "$dir/err3.txt"' "degenerate camera is a usage error with a message"
# an empty cloud gives a background-only image
printf 'ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n' > "$dir/empty.ply"
"$bin" render "$dir/empty.ply" -o "$dir/empty.png" --size 32x32 --quiet --style sketchy
check '[ $? -eq 0 ] && [ "$(png_w "$dir/empty.png")" -eq 32 ]' "empty cloud renders the background"
"$bin" render "$dir/empty.ply" -o "$dir/empty-lines.png" --size 32x32 --quiet --style lines
check '[ $? -eq 0 ] && cmp -s "$dir/empty.png" "$dir/empty-lines.png"' "empty cloud, lines style: the same background image"
# --look (the library's looks, look.h): sepia's paper on an empty cloud is --background 244,234,212;
# a background given beside it wins; comic on the cube is cartoon with outlines 3.5 px, byte for byte;
# --look with --style and an unknown look are usage errors naming the choices
"$bin" render "$dir/empty.ply" -o "$dir/sepia.png" --size 32x32 --quiet --look sepia
"$bin" render "$dir/empty.ply" -o "$dir/cream.png" --size 32x32 --quiet --style sketchy --background 244,234,212
check '[ -s "$dir/sepia.png" ] && cmp -s "$dir/sepia.png" "$dir/cream.png"' "--look sepia: its cream paper"
"$bin" render "$dir/empty.ply" -o "$dir/sepia-black.png" --size 32x32 --quiet --look sepia --background 0,0,0
"$bin" render "$dir/empty.ply" -o "$dir/black.png" --size 32x32 --quiet --style sketchy --background 0,0,0
check '[ -s "$dir/black.png" ] && cmp -s "$dir/sepia-black.png" "$dir/black.png"' "--look sepia --background 0,0,0: the given black wins"
"$bin" render "$dir/cube.ply" -o "$dir/comic.png" --size 120x90 --quiet --look comic
"$bin" render "$dir/cube.ply" -o "$dir/cartoon35.png" --size 120x90 --quiet --style cartoon --outline on --outline-width 3.5
check '[ -s "$dir/comic.png" ] && cmp -s "$dir/comic.png" "$dir/cartoon35.png"' "--look comic is cartoon with 3.5 px outlines"
"$bin" render "$dir/cube.ply" -o "$dir/cartoon.png" --size 120x90 --quiet --style cartoon
check '[ -s "$dir/cartoon.png" ] && ! cmp -s "$dir/comic.png" "$dir/cartoon.png"' "--look comic differs from cartoon's default outline"
"$bin" render "$dir/cube.ply" -o "$dir/x.png" --look comic --style sketchy 2> "$dir/err-look.txt"
check '[ $? -eq 2 ] && grep -q "give --look or --style" "$dir/err-look.txt"' "--look with --style exits 2"
"$bin" render "$dir/cube.ply" -o "$dir/x.png" --look crayon 2> "$dir/err-look2.txt"
check '[ $? -eq 2 ] && grep -q "pencil, contour" "$dir/err-look2.txt"' "an unknown look exits 2 and lists the looks"
# painterly: features computed on the fly, --paint-bins
"$bin" render "$dir/cube.ply" -o "$dir/paint.png" --size 120x90 --style painterly --paint-bins 3 --quiet
check '[ $? -eq 0 ] && [ "$(png_w "$dir/paint.png")" -eq 120 ]' "painterly renders (--paint-bins 3)"
"$bin" render "$dir/cube.ply" -o "$dir/x.png" --style painterly --paint-bins 17 > /dev/null 2>&1
check '[ $? -eq 2 ]' "--paint-bins 17 is a usage error"
# brush (stroke-based splatting): sizes, clusters and normals prepared on the fly; presets by name
"$bin" render "$dir/cube.ply" -o "$dir/brush.png" --size 120x90 --style brush --brush bristle --brush-scale 2 2> "$dir/brush.txt"
check '[ $? -eq 0 ] && [ "$(png_w "$dir/brush.png")" -eq 120 ] && grep -q "clusters, mean brush size" "$dir/brush.txt"' "brush renders (--brush bristle, the stage reported)"
"$bin" render "$dir/cube.ply" -o "$dir/x.png" --style brush --brush sponge 2> "$dir/brush-bad.txt"
check '[ $? -eq 2 ] && grep -q "bristle | flat | round" "$dir/brush-bad.txt"' "--brush sponge: a usage error naming the presets"
"$bin" render "$dir/cube.ply" -o "$dir/x.png" --style brush --brush-k 65 > /dev/null 2>&1
check '[ $? -eq 2 ]' "--brush-k 65 is a usage error"
# hierarchy (Chi & Lee): the sphere tree built on the fly; tonal art maps by name; an importance map
"$bin" render "$dir/cube.ply" -o "$dir/hier.png" --size 120x90 --style hierarchy --tam hatch --borders 0.01 --hier-layers 2 2> "$dir/hier.txt"
check '[ $? -eq 0 ] && [ "$(png_w "$dir/hier.png")" -eq 120 ] && grep -q "leaf spheres, .* regions" "$dir/hier.txt"' "hierarchy renders (--tam hatch, borders, two layers; the tree reported)"
"$bin" render "$dir/cube.ply" -o "$dir/x.png" --style hierarchy --tam crayon 2> "$dir/hier-bad.txt"
check '[ $? -eq 2 ] && grep -q "paint, hatch or dots" "$dir/hier-bad.txt"' "--tam crayon: a usage error naming the maps"
"$bin" render "$dir/cube.ply" -o "$dir/x.png" --style hierarchy --stroke-px 0.5 > /dev/null 2>&1
check '[ $? -eq 2 ]' "--stroke-px 0.5 is a usage error"
"$bin" render "$dir/cube.ply" -o "$dir/x.png" --style hierarchy --importance "$dir/no-such.png" 2> "$dir/imp-bad.txt"
check '[ $? -ne 0 ] && grep -q "no-such.png" "$dir/imp-bad.txt"' "--importance with a missing file: an error naming it"
"$bin" render "$dir/cube.ply" -o "$dir/hier-imp.png" --size 120x90 --style hierarchy --importance "$dir/hier.png" --silhouette-deg -1 2> /dev/null
check '[ $? -eq 0 ] && [ "$(png_w "$dir/hier-imp.png")" -eq 120 ]' "--importance with a PNG (any colour type) and silhouettes off"
"$bin" render "$dir/cube.ply" -o "$dir/x.png" --style Brushy 2> "$dir/style-bad.txt"
check '[ $? -eq 2 ] && grep -q "painterly, brush, hierarchy" "$dir/style-bad.txt"' "--style Brushy: the message lists the library's styles"
# tiled snapshots: forced 64-pixel tiles report progress per tile; an 8K image (7680x4320) renders
"$bin" render "$dir/cube.ply" -o "$dir/tiled.png" --size 200x150 --max-tile 64 2> "$dir/tiles.txt"
check '[ $? -eq 0 ] && [ "$(png_w "$dir/tiled.png")" -eq 200 ] && [ "$(grep -c "^render: tile [0-9]*/[0-9]*" "$dir/tiles.txt")" -ge 12 ]' "--max-tile 64: tiles with progress per tile"
"$bin" render "$dir/cube.ply" -o "$dir/tiled-q.png" --size 200x150 --max-tile 64 --quiet 2> "$dir/tiles-q.txt"
check '[ $? -eq 0 ] && [ ! -s "$dir/tiles-q.txt" ]' "--quiet: no tile progress"
"$bin" render "$dir/cube.ply" -o "$dir/8k.png" --size 7680x4320 --quiet
check '[ $? -eq 0 ] && [ "$(png_w "$dir/8k.png")" -eq 7680 ] && [ "$(png_h "$dir/8k.png")" -eq 4320 ]' "8K snapshot 7680x4320"
rm -f "$dir/8k.png"
"$bin" render "$dir/cube.ply" -o "$dir/x.png" --max-tile 8 > /dev/null 2>&1
check '[ $? -eq 2 ]' "--max-tile 8 is a usage error"
# --style-map: a cube with segment labels (x < 0.5: 0, else 1), 0 -> points, default sketchy
awk '/^end_header/ { print "property int segment" } { print }' "$dir/cube.ply" | \
  awk 'BEGIN { body = 0 } body { split($0, f, " "); print $0, (f[1] < 5123457.289 ? 0 : 1); next } { print } /^end_header/ { body = 1 }' > "$dir/cube_seg.ply"
printf '# intermingled\n0 points\n* sketchy   # the rest\n\n' > "$dir/map.txt"
"$bin" render "$dir/cube_seg.ply" -o "$dir/map.png" --size 200x150 --style-map "$dir/map.txt" 2> "$dir/map-log.txt"
check '[ $? -eq 0 ] && [ "$(png_w "$dir/map.png")" -eq 200 ] && grep -q "computing features" "$dir/map-log.txt" && grep -q "style map" "$dir/map-log.txt"' "--style-map renders (features computed for the mapped sketchy)"
printf '0 points\n1 points\n' > "$dir/map-pts.txt"
"$bin" render "$dir/cube_seg.ply" -o "$dir/map-pts.png" --size 200x150 --style-map "$dir/map-pts.txt" 2> "$dir/map-pts-log.txt"
check '[ $? -eq 0 ] && ! grep -q "computing" "$dir/map-pts-log.txt"' "--style-map with points only computes no features"
printf '0 points\n1 nosuch\n' > "$dir/map-bad.txt"
"$bin" render "$dir/cube_seg.ply" -o "$dir/x.png" --style-map "$dir/map-bad.txt" 2> "$dir/map-bad-log.txt"
check '[ $? -eq 2 ] && grep -q "map-bad.txt:2: unknown style .nosuch." "$dir/map-bad-log.txt"' "--style-map: unknown style names its line"
printf 'x points\n' > "$dir/map-bad2.txt"
"$bin" render "$dir/cube_seg.ply" -o "$dir/x.png" --style-map "$dir/map-bad2.txt" 2> "$dir/map-bad2-log.txt"
check '[ $? -eq 2 ] && grep -q "map-bad2.txt:1: label .x." "$dir/map-bad2-log.txt"' "--style-map: bad label names its line"
printf '0 points sketchy\n' > "$dir/map-bad3.txt"
"$bin" render "$dir/cube_seg.ply" -o "$dir/x.png" --style-map "$dir/map-bad3.txt" > /dev/null 2>&1
check '[ $? -eq 2 ]' "--style-map: three words is an error"
"$bin" render "$dir/cube_seg.ply" -o "$dir/x.png" --style-map "$dir/nonexistent.txt" > /dev/null 2>&1
check '[ $? -eq 2 ]' "--style-map: missing file"
# camera files: the automatic camera written and read back gives the same image; lines' SVG
# takes the same file; a bad line is a usage error naming FILE:LINE
"$bin" render "$dir/cube.ply" -o "$dir/cam_auto.png" --size 120x90 --save-camera "$dir/cam.txt" --quiet
"$bin" render "$dir/cube.ply" -o "$dir/cam_file.png" --size 120x90 --camera "$dir/cam.txt" --quiet
check 'grep -q "^eye " "$dir/cam.txt" && cmp -s "$dir/cam_auto.png" "$dir/cam_file.png"' "--save-camera then --camera: the same image"
"$bin" lines "$dir/cube.ply" -o "$dir/cam_lines.obj" --svg "$dir/cam_lines.svg" --camera "$dir/cam.txt" --quiet
check '[ $? -eq 0 ] && grep -q "<svg" "$dir/cam_lines.svg"' "lines --camera FILE"
printf 'eye 1 2 3\ntarget 0 0\n' > "$dir/badcam.txt"
"$bin" render "$dir/cube.ply" -o "$dir/x.png" --camera "$dir/badcam.txt" 2> "$dir/badcam.log"
check '[ $? -eq 2 ] && grep -q "badcam.txt:2" "$dir/badcam.log"' "bad camera file: exit 2 with FILE:LINE"
"$bin" render --help > "$dir/help.txt"   # (a file: grep -q closing a pipe early would SIGPIPE it)
check '[ $? -eq 0 ] && grep -q "usage: pointnpr render" "$dir/help.txt" && grep -q -- "--outline-jump F .*(default 3, " "$dir/help.txt"' "--help (defaults read from the library)"
# the plan: cartoon on a coloured cloud without labels segments it (JSEG), as explain says
"$bin" explain "$dir/cube.ply" --style cartoon > "$dir/explain-cartoon.txt"
check 'grep -Eq "^  segments +run .*method jseg" "$dir/explain-cartoon.txt"' "explain: cartoon runs JSEG on a coloured cloud"
"$bin" render "$dir/cube.ply" -o "$dir/cartoon.png" --style cartoon --size 160x120 2> "$dir/cartoon-log.txt"
check '[ $? -eq 0 ] && grep -q "segmenting the colours (JSEG)" "$dir/cartoon-log.txt" && grep -q "computing normals" "$dir/cartoon-log.txt"' "render cartoon: JSEG segments and normals for the outline, as planned"
"$bin" render "$dir/cube.ply" -o "$dir/cartoon-off.png" --style cartoon --outline off --size 160x120 2> "$dir/cartoon-off-log.txt"
check '[ $? -eq 0 ] && ! grep -q "computing normals" "$dir/cartoon-off-log.txt"' "cartoon --outline off: no normals needed"
"$bin" explain "$dir/cube.ply" --style cartoon --outline off > "$dir/explain-off.txt"
check 'grep -Eq "^  normals \(PCA\) +skip" "$dir/explain-off.txt"' "explain --outline off: no normals"
# new options: bad values are usage errors naming the option
for bad in "--outline maybe" "--outline-width 0" "--outline-width 100" "--outline-jump -1" "--tone sepia" "--tone-gamma 0" "--light 0,0,0" "--light 1,2"; do
  "$bin" render "$dir/cube.ply" -o "$dir/x.png" $bad 2> "$dir/bad-opt.log"
  check '[ $? -eq 2 ] && grep -q -- "${bad%% *}" "$dir/bad-opt.log"' "render $bad: exit 2 naming the option"
done
"$bin" render "$dir/cube.ply" -o "$dir/light.png" --style sketchy --tone light --tone-gamma 1.5 --light 1,0,1 --outline-width 3 --size 120x90 --quiet
check '[ $? -eq 0 ] && [ "$(png_w "$dir/light.png")" -eq 120 ]' "tone and outline options render"

# vector drawings (docs/export.md): SVG with named layers, PDF with the drawing's page size,
# plotter order and merged hatches reported; fill styles and PNG-only options refused up front
"$bin" render "$dir/cube.ply" -o "$dir/sketch.svg" --style sketchy --size 200x150 --plot-order --merge-hatches 2> "$dir/svg.log"
rc=$?; check '[ $rc -eq 0 ] && grep -q "<svg" "$dir/sketch.svg" && grep -q "inkscape:label=\"strokes\"" "$dir/sketch.svg"' "sketchy SVG with a strokes layer ($(cat "$dir/svg.log"))"
check 'grep -q "pen-up travel" "$dir/svg.log" && grep -q "hatches merged" "$dir/svg.log"' "plotter order and merging reported"
"$bin" render "$dir/cube.ply" -o "$dir/plot.svg" --style sketchy --size 200x150 --min-mark 1000 2> "$dir/mm.log"
check '[ $? -eq 0 ] && grep -q "under 1000 px left out" "$dir/mm.log" && ! grep -q "<path" "$dir/plot.svg"' "--min-mark 1000 leaves no stroke"
check 'grep -q "width=\"200px\" height=\"150px\"" "$dir/sketch.svg"' "SVG is 200x150 px"
"$bin" render "$dir/cube.ply" -o "$dir/dots.pdf" --style stipple --size 200x150 --quiet
check '[ $? -eq 0 ] && [ "$(head -c 5 "$dir/dots.pdf")" = "%PDF-" ]' "stipple PDF written"
if command -v pdfinfo > /dev/null; then
  check 'pdfinfo "$dir/dots.pdf" | grep -q "Page size: *150 x 112.5 pts"' "PDF page is 200x150 px at 0.75 pt"
fi
"$bin" render "$dir/cube.ply" -o "$dir/fill.svg" --style points --quiet 2> "$dir/fill.log"
check '[ $? -eq 2 ] && grep -q "fills areas" "$dir/fill.log" && [ ! -e "$dir/fill.svg" ]' "points as SVG refused before any work"
# a style map as vectors: its styles must draw strokes or areas of colour; the default (sketchy)
# draws the labels the map leaves out
printf '0 stipple\n' > "$dir/map-vec.txt"
"$bin" render "$dir/cube_seg.ply" -o "$dir/map.svg" --size 200x150 --style-map "$dir/map-vec.txt" --style sketchy 2> "$dir/map-vec.log"
check '[ $? -eq 0 ] && grep -q "inkscape:label=\"dots\"" "$dir/map.svg" && grep -q "inkscape:label=\"strokes\"" "$dir/map.svg" && grep -q "style map" "$dir/map-vec.log"' "a style map as SVG: dots and strokes"
"$bin" render "$dir/cube_seg.ply" -o "$dir/map-fill.svg" --size 200x150 --style-map "$dir/map.txt" --quiet 2> "$dir/map-fill.log"
check '[ $? -eq 2 ] && grep -q "entry 1 (label 0): style .points. fills areas" "$dir/map-fill.log" && [ ! -e "$dir/map-fill.svg" ]' "a style map with points as SVG refused before any work"
"$bin" render "$dir/cube.ply" -o "$dir/faint.svg" --style lines --faint 0.3 --quiet 2> "$dir/faint.log"
check '[ $? -eq 2 ] && grep -q "faint" "$dir/faint.log" && [ ! -e "$dir/faint.svg" ]' "lines --faint as SVG refused"
"$bin" render "$dir/cube.ply" -o "$dir/x.png" --plot-order --quiet 2> "$dir/po.log"
check '[ $? -eq 2 ] && grep -q "vector output" "$dir/po.log"' "--plot-order with a PNG refused"
exit $fail
