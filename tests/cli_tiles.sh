#!/bin/bash
# Tiled features from the command line (docs/tiles.md): a generated 2.5D scan of 14 400 points,
# in memory and in tiles (--tile-points, and the manifest's jobs run by a shell, then merge-tiles):
# the bodies of the results are byte-identical and all but a few points are certified; --tiles
# sizes tiles from --memory-limit; refusals name the file and the reason; a folder of tiles joined
# one at a time; render --sample draws a uniform sample, the same at every run; segment
# --method components in tiles equals the run in memory; a file ordered for drawing samples as
# the ordinary file does, reading part of it.
# usage: cli_tiles.sh POINTNPR SCRATCH
bin=$1
dir=$2/cli_tiles
source "$(dirname "$0")/lib_cli.sh"
rm -rf "$dir" && mkdir -p "$dir/bin" || exit 1
ln -s "$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")" "$dir/bin/pointnpr"
export PATH="$dir/bin:$PATH"

# a terrain: a ridge along y, a step across x, jitter; ascii, then binary
awk 'BEGIN { srand(7); m = 120; print "ply\nformat ascii 1.0\nelement vertex " m * m
  print "property float x\nproperty float y\nproperty float z\nend_header"
  for (i = 0; i < m; i++) for (j = 0; j < m; j++) {
    x = (i + 0.4 * rand()) / 12; y = (j + 0.4 * rand()) / 12
    r = 0.8 - 0.6 * (x > 3.3 ? x - 3.3 : 3.3 - x); if (r < 0) r = 0
    printf "%.6f %.6f %.6f\n", x, y, r + (y > 6.1 ? 0.5 : 0) }}' > "$dir/ascii.ply"
pointnpr convert "$dir/ascii.ply" -o "$dir/in.ply" --quiet || { echo "FAILED: convert"; exit 1; }
opts=(--threshold 0.3 --viewpoint 5,5,50)

# body_same A B: the two PLY files' bodies (after end_header) are byte-identical
body_same() {
  local a b
  a=$(grep -abo -m1 end_header "$1" | cut -d: -f1) b=$(grep -abo -m1 end_header "$2" | cut -d: -f1)
  [ -n "$a" ] && [ -n "$b" ] && cmp -s -i "$((a + 11)):$((b + 11))" "$1" "$2"
}

pointnpr features "$dir/in.ply" -o "$dir/mem.ply" "${opts[@]}" --quiet
pointnpr features "$dir/in.ply" -o "$dir/tiled.ply" "${opts[@]}" --tile-points 5000 2> "$dir/tiled.log"
check '[ $? -eq 0 ]' "features --tile-points exits 0"
ntiles=$(sed -n 's/.*points in \([0-9]*\) tiles.*/\1/p' "$dir/tiled.log")
check '[ "${ntiles:-0}" -ge 3 ]' "at most 5000 points a tile: at least 3 tiles (got '${ntiles}')"
unsure=$(sed -n "s/.*14400 points from $ntiles tiles; \([0-9]*\) not certain.*/\1/p" "$dir/tiled.log")
check '[ -n "$unsure" ] && [ "$unsure" -lt 20 ]' "at most a few points not certified (got '$unsure')"
check 'body_same "$dir/mem.ply" "$dir/tiled.ply"' "tiled result equals the in-memory one"
check '[ $(ls -a "$dir" | grep -c tiles\\.) -eq 0 ]' "the work folder is removed"

# --tiles sizes them from --memory-limit (beyond what the process holds): all in one tile under a
# large limit, none under a limit the process itself exceeds (test_tiles checks the sizes)
pointnpr features "$dir/in.ply" -o "$dir/big.ply" "${opts[@]}" --tiles --memory-limit 8G 2> "$dir/big.log"
check '[ $? -eq 0 ] && grep -q "14400 points in 1 tiles" "$dir/big.log" && body_same "$dir/mem.ply" "$dir/big.ply"' \
  "--tiles under 8G: one tile, the same result"
pointnpr features "$dir/in.ply" -o "$dir/bad.ply" --tiles --memory-limit 1M 2> "$dir/err.log"
check '[ $? -eq 1 ] && grep -q "in.ply: a memory limit of .* leaves no room for a tile" "$dir/err.log"' \
  "--tiles under 1M: refused with the reason"

# the manifest: independent jobs, then the merge
pointnpr features "$dir/in.ply" -o "$dir/manifest.ply" "${opts[@]}" --tile-points 4000 --manifest "$dir/jobs" --quiet
check '[ -f "$dir/jobs/jobs.txt" ] && [ -f "$dir/jobs/merge.txt" ]' "--manifest writes jobs.txt and merge.txt"
njobs=$(wc -l < "$dir/jobs/jobs.txt")
check '[ "$njobs" -ge 4 ]' "at most 4000 points a tile: at least 4 jobs (got $njobs)"
check '[ ! -e "$dir/manifest.ply" ]' "--manifest runs nothing"
(cd "$dir" && while read -r job; do eval "$job --quiet" || exit 1; done < jobs/jobs.txt)
check '[ $? -eq 0 ]' "every job of jobs.txt runs"
bash "$dir/jobs/merge.txt" 2> "$dir/merge.log"
check '[ $? -eq 0 ]' "merge.txt runs"
check 'body_same "$dir/mem.ply" "$dir/manifest.ply"' "merged jobs equal the in-memory result"

# without --viewpoint each tile orients its own normals; the merge makes them agree (--seams)
pointnpr features "$dir/in.ply" -o "$dir/mem_nv.ply" --threshold 0.3 --quiet
pointnpr features "$dir/in.ply" -o "$dir/tiled_nv.ply" --threshold 0.3 --tile-points 5000 --quiet
check 'body_same "$dir/mem_nv.ply" "$dir/tiled_nv.ply"' "without a viewpoint: tiled equals in memory"
pointnpr features "$dir/in.ply" -o "$dir/nv.ply" --threshold 0.3 --tile-points 5000 --manifest "$dir/jobs_nv" --quiet
check 'grep -q "merge-tiles --points 14400 --seams" "$dir/jobs_nv/merge.txt"' "merge.txt asks for the seams without a viewpoint"
check '! grep -q -- "--seams" "$dir/jobs/merge.txt"' "and not with one"

# refusals
tiles=("$dir"/jobs/tile_*.ply)
pointnpr merge-tiles --points 14400 -o "$dir/bad.ply" "${tiles[@]:1}" 2> "$dir/err.log"
check '[ $? -eq 1 ] && grep -q "is in no tile" "$dir/err.log" && [ ! -e "$dir/bad.ply" ]' "a missing tile is refused, nothing written"
pointnpr merge-tiles --points 14400 -o "$dir/bad.ply" "${tiles[@]}" "${tiles[0]}" 2> "$dir/err.log"
check '[ $? -eq 1 ] && grep -q "comes twice" "$dir/err.log"' "a tile twice is refused"
pointnpr merge-tiles --points 14400 -o "$dir/bad.ply" "$dir/in.ply" 2> "$dir/err.log"
check '[ $? -eq 1 ] && grep -q "in.ply: no uint property source_index" "$dir/err.log"' "a cloud that is no tile is refused"
pointnpr features "$dir/ascii.ply" -o "$dir/bad.ply" --tiles 2> "$dir/err.log"
check '[ $? -eq 1 ] && grep -q "ascii.ply.*binary" "$dir/err.log"' "an ascii PLY is refused, naming the file"
pointnpr features "$dir/in.ply" -o "$dir/bad.ply" --tile-grid 0,0,1,1,9999,1,0,0,0 --tile 0,0,1,1 2> "$dir/err.log"
check '[ $? -eq 2 ] && grep -q "tile-grid" "$dir/err.log"' "a bogus tile is a usage error"
pointnpr features "$dir/in.ply" -o - --tiles > /dev/null 2> "$dir/err.log"
check '[ $? -eq 2 ] && grep -q "must be a file" "$dir/err.log"' "tiles refuse standard output"
pointnpr features "$dir/in.ply" -o "$dir/bad.pcd" --tile-points 5000 2> "$dir/err.log"
check '[ $? -eq 2 ] && grep -q "must end in .ply" "$dir/err.log" && [ ! -e "$dir/bad.pcd" ]' "tiles refuse a PCD output"
pointnpr features "$dir/in.ply" -o "$dir/bad.ply" --tile-grid 0,0,1,1,2,2,0,0,0 --tile 0,0,-1,1 2> "$dir/err.log"
check '[ $? -eq 2 ]' "a tile with negative cells is a usage error"

# an empty cloud: one tile, no halo; its manifest's jobs run
printf 'ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n' > "$dir/empty.ply"
pointnpr features "$dir/empty.ply" -o "$dir/empty_f.ply" --tile-points 5000 --manifest "$dir/jobs_empty" --quiet
(while read -r job; do eval "$job --quiet" || exit 1; done < "$dir/jobs_empty/jobs.txt") && bash "$dir/jobs_empty/merge.txt" 2> /dev/null
check '[ $? -eq 0 ] && [ -f "$dir/empty_f.ply" ]' "an empty cloud's manifest runs and merges"

pointnpr segment "$dir/empty.ply" -o "$dir/empty_s.ply" --method components --tile-points 5000 --quiet
check '[ $? -eq 0 ] && [ "$(head -c 200 "$dir/empty_s.ply" | grep -a -c "element vertex 0")" -eq 1 ]' \
  "an empty cloud's components in tiles: an empty result"

# a folder of tiles: convert joins them one at a time when they would not fit together (here a
# 1 KiB limit) or with --stream; the records are those of the join in memory; then features runs
# in tiles on the joined file as on any other
mkdir -p "$dir/folder" && cp "$dir/in.ply" "$dir/folder/a.ply"
pointnpr convert "$dir/in.ply" "$dir/in.ply" "$dir/in.ply" -o "$dir/joined_mem.ply" --quiet
pointnpr convert "$dir/in.ply" "$dir/in.ply" "$dir/in.ply" -o "$dir/joined.ply" --memory-limit 1K 2> "$dir/join.log"
check '[ $? -eq 0 ] && grep -q "one at a time" "$dir/join.log"' "convert joins one at a time when the inputs do not fit"
check 'body_same "$dir/joined_mem.ply" "$dir/joined.ply"' "the join's records equal the join in memory"
check '[ "$(head -c 300 "$dir/joined.ply" | grep -a -c "element vertex 43200")" -eq 1 ]' "the joined count is written"
pointnpr convert "$dir/in.ply" "$dir/mem.ply" -o "$dir/joined.ply" --stream 2> "$dir/err.log"
check '[ $? -eq 1 ] && grep -q "mem.ply: its points have other properties" "$dir/err.log" && body_same "$dir/joined_mem.ply" "$dir/joined.ply"' \
  "inputs of other properties are refused, naming the file, the output kept"
pointnpr convert "$dir/in.ply" "$dir/in.ply" -o - --stream > /dev/null 2> "$dir/err.log"
check '[ $? -eq 2 ] && grep -q "writes a .ply file" "$dir/err.log"' "--stream to standard output is a usage error"
pointnpr render "$dir/folder" -o "$dir/folder.png" 2> "$dir/err.log"
check '[ $? -eq 1 ] && grep -q "pointnpr convert" "$dir/err.log"' "render of a folder says how to join it"

# segment --method components in tiles: 4 x 4 coloured patches (jittered grids) and a thin line
# across all of them above; in memory, in tiles and through the manifest's jobs, byte-identical
awk 'BEGIN { srand(11); n = 16 * 400 + 600; print "ply\nformat ascii 1.0\nelement vertex " n
  print "property float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green"
  print "property uchar blue\nend_header"
  for (k = 0; k < 16; k++) for (i = 0; i < 400; i++)
    printf "%.5f %.5f 0 %d %d %d\n", (k % 4) * 1.5 + (i % 20 + 0.3 * rand()) * 0.05,
      int(k / 4) * 1.5 + (int(i / 20) + 0.3 * rand()) * 0.05, 15 * k, 255 - 15 * k, i % 256
  for (i = 0; i < 600; i++) printf "%.5f 2.9 1 7 7 7\n", i * 0.01 }' > "$dir/patches_a.ply"
pointnpr convert "$dir/patches_a.ply" -o "$dir/patches.ply" --quiet
pointnpr segment "$dir/patches.ply" -o "$dir/seg_mem.ply" --method components 2> "$dir/seg_mem.log"
check 'grep -q "17 segments" "$dir/seg_mem.log"' "16 patches and the line: 17 components in memory"
pointnpr segment "$dir/patches.ply" -o "$dir/seg_tiled.ply" --method components --tile-points 1000 2> "$dir/seg.log"
ntiles=$(sed -n 's/.*points in \([0-9]*\) tiles.*/\1/p' "$dir/seg.log")
check '[ "${ntiles:-0}" -ge 4 ] && grep -q "^17 segments" "$dir/seg.log"' "in $ntiles tiles: 17 segments"
check 'body_same "$dir/seg_mem.ply" "$dir/seg_tiled.ply"' "segments in tiles equal the run in memory"
pointnpr segment "$dir/patches.ply" -o "$dir/seg_jobs.ply" --method components --tile-points 1000 --manifest "$dir/segjobs" --quiet
check 'grep -q -- "--radius" "$dir/segjobs/jobs.txt" && grep -q "merge-tiles --points 7000 --segments" "$dir/segjobs/merge.txt"' \
  "the manifest's jobs get the automatic distance, its merge --segments"
(cd "$dir" && while read -r job; do eval "$job --quiet" || exit 1; done < segjobs/jobs.txt) && bash "$dir/segjobs/merge.txt" 2> /dev/null
check '[ $? -eq 0 ] && body_same "$dir/seg_mem.ply" "$dir/seg_jobs.ply"' "the manifest's jobs and merge equal the run in memory"
segtiles=("$dir"/segjobs/tile_*.ply)
pointnpr merge-tiles --points 7000 --segments -o "$dir/bad.ply" "${segtiles[@]:1}" 2> "$dir/err.log"
check '[ $? -eq 1 ] && grep -q "in no tile" "$dir/err.log" && [ ! -e "$dir/bad.ply" ]' "a missing segment tile is refused"
pointnpr merge-tiles --points 7000 --segments --seams -o "$dir/bad.ply" "${segtiles[@]}" 2> "$dir/err.log"
check '[ $? -eq 2 ]' "--seams and --segments together are a usage error"
pointnpr merge-tiles --points 7000 -o "$dir/bad.ply" "${segtiles[@]}" 2> "$dir/err.log"
check '[ $? -eq 1 ] && grep -q "tile_00000.ply: a tile of .pointnpr segment.*--segments" "$dir/err.log" && [ ! -e "$dir/bad.ply" ]' \
  "segment tiles merged without --segments are refused"
pointnpr segment "$dir/patches.ply" -o "$dir/seg_far.ply" --method components --radius 2 --tiles --memory-limit 40M 2> "$dir/far.log"
check '[ $? -eq 0 ] && grep -q "warning: the distance 2 is large against the tiles" "$dir/far.log"' \
  "a distance large against the tiles is warned of"
for bad in "--method jseg" "--method components --min-size 5" "--method components --split 0.1" \
           "--method components --segments 4" "--method components --ascii"; do
  pointnpr segment "$dir/patches.ply" -o "$dir/bad.ply" $bad --tile-points 1000 2> "$dir/err.log"
  check '[ $? -eq 2 ] && grep -q "in tiles:" "$dir/err.log" && [ ! -e "$dir/bad.ply" ]' "segment $bad in tiles is refused with the reason"
done
pointnpr segment "$dir/patches.ply" -o "$dir/bad.ply" --method components --radius 0.2 --tile-grid 0,0,1,1,2,2,0,0,0 \
  --tile 0,0,1,1 --halo 0.1 2> "$dir/err.log"
check '[ $? -eq 2 ] && grep -q "needs a halo of" "$dir/err.log"' "a job's halo smaller than the distance is refused"

# render --sample: a uniform share of the points, the same at every run (the automatic share under
# --memory-limit takes the same path)
if built_with_render "$bin"; then
  pointnpr render "$dir/mem.ply" -o "$dir/sample.png" --size 160x120 --sample 0.25 2> "$dir/sample.log"
  check '[ $? -eq 0 ] && [ -s "$dir/sample.png" ]' "render --sample draws"
  kept=$(sed -n 's/.*uniform sample of \([0-9]*\) of 14400 points.*/\1/p' "$dir/sample.log")
  check '[ "${kept:-0}" -gt 3240 ] && [ "${kept:-0}" -lt 3960 ]' "--sample 0.25 keeps about 3600 of 14400 points (got '$kept')"
  pointnpr render "$dir/mem.ply" -o "$dir/sample2.png" --size 160x120 --sample 0.25 --quiet
  check 'cmp -s "$dir/sample.png" "$dir/sample2.png"' "the same sample at every run"
  # by the view: a camera 6 above (6, 5) looking down keeps the points in its cone (the diagonal's
  # half-angle, 15 % wider) and, asked for more than those, all of them: counted here from the text
  pointnpr render "$dir/mem.ply" -o "$dir/view.png" --size 160x120 --sample 0.9 --eye 6,5,6 --target 6,5,0 2> "$dir/view.log"
  kept=$(sed -n 's/.*sample by the view .* of \([0-9]*\) of 14400 points.*/\1/p' "$dir/view.log")
  want=$(awk 'BEGIN { ty = sin(3.14159265358979 / 8) / cos(3.14159265358979 / 8); tx = ty * 160 / 120
    t2 = 1.15 * 1.15 * (tx * tx + ty * ty) } NR > 7 { d = 6 - $3; r2 = ($1 - 6) ^ 2 + ($2 - 5) ^ 2
    if (d > 0 && r2 <= d * d * t2) n++ } END { print n }' "$dir/ascii.ply")
  check '[ -n "$kept" ] && [ "$kept" -ge $((want - 2)) ] && [ "$kept" -le $((want + 2)) ] && [ "$want" -lt 14000 ]' \
    "the sample by the view keeps the $want points in view (got '$kept')"
  # by a path's frames: two frames (1 s at 1 frame/s), the cameras of the two keys, keep the points
  # in either cone
  printf 'time 0\neye 6 5 6\ntarget 6 5 0\nup 0 1 0\ntime 1\neye 2 2 6\ntarget 2 2 0\n' > "$dir/two.campath"
  pointnpr animate "$dir/mem.ply" -o "$dir/frames/" --camera-path "$dir/two.campath" --fps 1 --size 160x120 \
    --sample 0.9 2> "$dir/path.log"
  kept=$(sed -n "s/.*sample by the frames' views .* of \([0-9]*\) of 14400 points.*/\1/p" "$dir/path.log")
  want=$(awk 'BEGIN { ty = sin(3.14159265358979 / 8) / cos(3.14159265358979 / 8); tx = ty * 160 / 120
    t2 = 1.15 * 1.15 * (tx * tx + ty * ty) } NR > 7 { d = 6 - $3; ra = ($1 - 6) ^ 2 + ($2 - 5) ^ 2
    rb = ($1 - 2) ^ 2 + ($2 - 2) ^ 2; if (d > 0 && (ra <= d * d * t2 || rb <= d * d * t2)) n++ } END { print n }' "$dir/ascii.ply")
  check '[ -n "$kept" ] && [ "$kept" -ge $((want - 2)) ] && [ "$kept" -le $((want + 2)) ] && [ "$want" -lt 14000 ] &&
         [ -s "$dir/frames/frame-00001.png" ]' "the sample by a path's two frames keeps the $want points in their views (got '$kept')"
  pointnpr render "$dir/mem.ply" -o "$dir/at1.png" --size 160x120 --sample 0.9 --camera-path "$dir/two.campath" \
    --camera-at 0 2> "$dir/at.log"
  check 'grep -q "sample by the view .* of $(sed -n "s/.*sample by the view .* of \([0-9]*\) of 14400.*/\1/p" "$dir/view.log") of 14400" "$dir/at.log"' \
    "render --camera-path --camera-at 0 samples by that frame's view as --eye/--target do"
  # a preset's frames come from a uniform preview of the cloud: the sample follows them, and the
  # path is about the one made from the whole cloud (every number within 0.01 of the scene's 15)
  pointnpr animate "$dir/mem.ply" -o "$dir/orbit/" --orbit --duration 1 --fps 2 --size 160x120 --sample 0.9 \
    --save-path "$dir/orbit_sampled.campath" 2> "$dir/orbit.log"
  pointnpr animate "$dir/mem.ply" --orbit --duration 1 --save-path "$dir/orbit_whole.campath" --quiet
  near=$(paste -d' ' "$dir/orbit_sampled.campath" "$dir/orbit_whole.campath" | awk '$1 == "eye" || $1 == "target" {
    n++; for (i = 2; i <= 4; i++) { d = $i - $(i + 4); if (d > 0.01 || d < -0.01) bad++ } } END { print n + 0, bad + 0 }')
  check '[ -s "$dir/orbit/frame-00001.png" ] && grep -q "sample by the frames. views" "$dir/orbit.log" &&
         [ "${near% *}" -gt 100 ] && [ "${near#* }" = 0 ]' \
    "animate --orbit samples by its frames, its path from the preview within 0.01 of the whole cloud's (eyes and targets, far ones: $near)"
  # a sample sized to a limit is not refused after reading (a 409 600-point plane without features:
  # the samples of 120M..150M had been refused by 1 to 2 MiB, the cloud as read estimated too low):
  # each limit draws a sample, or (a process that holds more, as under ASan) is refused before
  # reading; 150M draws either way; a limit that no sample fits is refused before reading
  awk 'BEGIN { n = 640; print "ply\nformat ascii 1.0\nelement vertex " n * n "\nproperty float x\nproperty float y"
    print "property float z\nend_header"; for (j = 0; j < n; j++) for (i = 0; i < n; i++)
    printf "%g %g %g\n", i * 0.05, j * 0.05, 0.3 * sin(i * 0.1) * cos(j * 0.07) }' > "$dir/plane.txt.ply"
  pointnpr convert "$dir/plane.txt.ply" -o "$dir/plane.ply" --quiet
  for lim in 120M 130M 135M 150M; do
    rm -f "$dir/lim.png"
    pointnpr render "$dir/plane.ply" -o "$dir/lim.png" --size 160x120 --memory-limit $lim 2> "$dir/lim.log"
    rc=$?
    check '{ [ $rc -eq 0 ] && grep -q "uniform sample" "$dir/lim.log"; } ||
           { [ $lim != 150M ] && [ $rc -eq 1 ] && grep -q "not even a sample" "$dir/lim.log" && [ ! -e "$dir/lim.png" ]; }' \
      "the uniform sample sized to --memory-limit $lim draws, or is refused before reading (rc $rc)"
  done
  rm -f "$dir/lim.png"
  pointnpr render "$dir/plane.ply" -o "$dir/lim.png" --size 160x120 --memory-limit 105M 2> "$dir/lim.log"
  check '[ $? -eq 1 ] && grep -q "not even a sample of its 409600 points fits" "$dir/lim.log" && ! grep -q "^read" "$dir/lim.log" &&
         [ ! -e "$dir/lim.png" ]' "a limit no sample fits is refused before reading"
  pointnpr render "$dir/ascii.ply" -o "$dir/bad.png" --size 160x120 --sample 0.25 2> "$dir/err.log"
  check '[ $? -eq 1 ] && grep -q "binary" "$dir/err.log"' "--sample of an ascii PLY is refused"

  # a file ordered for drawing (convert --lod): every point again, and the samples by the view and
  # the frames keep the same points in view as the pass over every point, reading only part of it
  pointnpr convert "$dir/mem.ply" -o "$dir/lod.ply" --lod --memory-limit 60M 2> "$dir/lod.log"
  check '[ $? -eq 0 ] && grep -q "14400 points ordered for drawing" "$dir/lod.log" &&
         [ "$(pointnpr info "$dir/lod.ply" 2>&1 | grep -c "14400")" -ge 1 ]' "convert --lod writes the 14400 points, an ordinary PLY to info"
  pointnpr render "$dir/lod.ply" -o "$dir/lod_view.png" --size 160x120 --sample 0.9 --eye 6,5,6 --target 6,5,0 2> "$dir/lod_view.log"
  kept=$(sed -n 's/.*sample by the view .* of \([0-9]*\) of 14400 points.*/\1/p' "$dir/lod_view.log")
  read_pc=$(sed -n 's/.*ordered for drawing: \([0-9.]*\)% of its points read.*/\1/p' "$dir/lod_view.log")
  check '[ -n "$kept" ] && [ "$kept" = "$(sed -n "s/.*sample by the view .* of \([0-9]*\) of 14400 points.*/\1/p" "$dir/view.log")" ] &&
         [ -n "$read_pc" ] && awk -v r="$read_pc" "BEGIN { exit !(r < 80) }"' \
    "the sample by the view of the ordered file keeps the same $kept points in view, reading $read_pc% of them"
  pointnpr animate "$dir/lod.ply" -o "$dir/lod_frames/" --camera-path "$dir/two.campath" --fps 1 --size 160x120 \
    --sample 0.9 2> "$dir/lod_path.log"
  check '[ "$(sed -n "s/.*sample by the frames. views .* of \([0-9]*\) of 14400 points.*/\1/p" "$dir/lod_path.log")" = \
          "$(sed -n "s/.*sample by the frames. views .* of \([0-9]*\) of 14400 points.*/\1/p" "$dir/path.log")" ] &&
         grep -q "ordered for drawing" "$dir/lod_path.log"' "the sample by a path's frames of the ordered file keeps the same points"
  pointnpr render "$dir/lod.ply" -o "$dir/lod_u.png" --size 160x120 --sample 0.25 2> "$dir/lod_u.log"
  kept=$(sed -n 's/.*uniform sample of \([0-9]*\) of 14400 points.*/\1/p' "$dir/lod_u.log")
  pointnpr render "$dir/lod.ply" -o "$dir/lod_u2.png" --size 160x120 --sample 0.25 --quiet
  check '[ "${kept:-0}" -gt 3240 ] && [ "${kept:-0}" -lt 3960 ] && cmp -s "$dir/lod_u.png" "$dir/lod_u2.png"' \
    "--sample 0.25 of the ordered file keeps about 3600 points, the same at every run (got '$kept')"
  pointnpr animate "$dir/lod.ply" -o "$dir/lod_orbit/" --orbit --duration 1 --fps 2 --size 160x120 --sample 0.9 2> "$dir/lod_orbit.log"
  check '[ -s "$dir/lod_orbit/frame-00001.png" ] && grep -q "sample by the frames. views" "$dir/lod_orbit.log"' \
    "animate --orbit of the ordered file samples by its frames"
  # far outliers in view (20 points 2 km below the camera, straight ahead) lie outside the grid,
  # in its last cell: the view reads them all and keeps them as the ordinary file does
  awk 'NR == 3 { print "element vertex 14420"; next } { print } END { for (i = 0; i < 20; i++) printf "%g 5 -2000\n", 5.9 + i * 0.01 }' \
    "$dir/ascii.ply" > "$dir/far.txt.ply"
  pointnpr convert "$dir/far.txt.ply" -o "$dir/far.ply" --quiet && pointnpr convert "$dir/far.ply" -o "$dir/far_lod.ply" --lod --quiet
  for f in far far_lod; do
    pointnpr render "$dir/$f.ply" -o "$dir/$f.png" --size 160x120 --sample 0.9 --eye 6,5,6 --target 6,5,0 2> "$dir/$f.log"
  done
  kept=$(sed -n 's/.*sample by the view .* of \([0-9]*\) of 14420 points.*/\1/p' "$dir/far_lod.log")
  check '[ -n "$kept" ] && [ "$kept" = "$(sed -n "s/.*sample by the view .* of \([0-9]*\) of 14420 points.*/\1/p" "$dir/far.log")" ] &&
         [ "$kept" = $(( $(sed -n "s/.*sample by the view .* of \([0-9]*\) of 14400 points.*/\1/p" "$dir/view.log") + 20 )) ] &&
         pointnpr info "$dir/far_lod.ply" | grep -q "20 points outside them"' \
    "far outliers in view, outside the ordered file's grid, are kept as the ordinary file keeps them (got '$kept')"
  # an index that lies (a run's count changed): a warning, and the file is read as an ordinary PLY
  cp "$dir/lod.ply" "$dir/lod_bad.ply"
  printf '\377' | dd of="$dir/lod_bad.ply" bs=1 seek=$(($(stat -c %s "$dir/lod.ply") - 2)) conv=notrunc 2> /dev/null
  pointnpr render "$dir/lod_bad.ply" -o "$dir/lod_bad.png" --size 160x120 --sample 0.9 --eye 6,5,6 --target 6,5,0 2> "$dir/lod_bad.log"
  check '[ $? -eq 0 ] && grep -q "lod_bad.ply: warning: its order for drawing cannot be used (.*index counts" "$dir/lod_bad.log" &&
         grep -q "of $(sed -n "s/.*sample by the view .* of \([0-9]*\) of 14400.*/\1/p" "$dir/view.log") of 14400" "$dir/lod_bad.log"' \
    "an ordered file whose index lies is read as an ordinary PLY, with a warning"
  pointnpr convert "$dir/mem.ply" "$dir/in.ply" -o "$dir/lod2.ply" --lod 2> "$dir/err.log"
  check '[ $? -eq 2 ] && grep -q "one binary PLY" "$dir/err.log" && [ ! -e "$dir/lod2.ply" ]' "convert --lod of two inputs is refused"
  pointnpr convert "$dir/ascii.ply" -o "$dir/lod2.ply" --lod 2> "$dir/err.log"
  check '[ $? -eq 1 ] && grep -q "ascii.ply.*binary" "$dir/err.log" && [ ! -e "$dir/lod2.ply" ]' "convert --lod of an ascii PLY is refused, naming it"
fi
exit $fail
