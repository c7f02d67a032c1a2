#!/usr/bin/env bash
# pointnpr animate end to end: frames of an orbit, a flyover and a path file; frame k equals
# `render --camera-path --camera-at t_k` (same pixels); a stopped-and-resumed animation equals an
# uninterrupted one; frames of other settings are not mixed in; the video through ffmpeg (skipped
# with a message when there is none); ffmpeg missing: a clear error and the frames kept; usage
# errors and FILE:LINE errors of path files.
#   bash cli_animate.sh /path/to/pointnpr SCRATCH_DIR        (exit 77: no headless GL here)
set -uo pipefail
bin=$1
dir=$2/cli_animate
rm -rf "$dir"; mkdir -p "$dir"
fail=0
check() { if ! eval "$1"; then echo "FAILED: $2" >&2; fail=1; fi; }
count() { ls "$1" 2>/dev/null | grep -c '^frame-[0-9]*\.png$'; }
same_frames() { # same_frames DIR1 DIR2 N: frames 0..N-1 identical
  local k f
  for ((k = 0; k < $3; k++)); do f=$(printf 'frame-%05d.png' $k); cmp -s "$1/$f" "$2/$f" || return 1; done
}

# a coloured box (spacing 0.05) at a georeferenced offset with a smaller box on top
awk 'BEGIN {
  n = 0
  for (i = 0; i <= 20; i++) for (j = 0; j <= 12; j++) for (k = 0; k <= 8; k++) {
    if (i > 0 && i < 20 && j > 0 && j < 12 && k > 0 && k < 8) continue
    line[n++] = sprintf("%.17g %.17g %.17g %d %d %d", 5123456.789 + i * 0.05, 4012345.678 + j * 0.05, 250.125 + k * 0.05, 200, 100 + i * 5, 50)
  }
  for (i = 0; i <= 6; i++) for (j = 0; j <= 6; j++) for (k = 1; k <= 6; k++) {
    if (i > 0 && i < 6 && j > 0 && j < 6 && k < 6) continue
    line[n++] = sprintf("%.17g %.17g %.17g %d %d %d", 5123457.1 + i * 0.05, 4012345.8 + j * 0.05, 250.525 + k * 0.05, 60, 90, 200)
  }
  print "ply"; print "format ascii 1.0"; print "element vertex " n
  print "property double x"; print "property double y"; print "property double z"
  print "property uchar red"; print "property uchar green"; print "property uchar blue"
  print "end_header"
  for (q = 0; q < n; q++) print line[q]
}' > "$dir/box.ply"
A="--size 160x120 --quiet"

# an orbit of 8 frames (loop: 2 s x 4 fps) in sketchy with outlines, its path saved
"$bin" animate "$dir/box.ply" -o "$dir/orbit/" --orbit --duration 2 --fps 4 --style sketchy --outline on \
  --save-path "$dir/orbit.campath" --size 160x120 2> "$dir/log.txt"
rc=$?
if [ $rc -ne 0 ] && grep -q "headless OpenGL" "$dir/log.txt"; then
  echo "cli_animate: skipped: $(cat "$dir/log.txt")" >&2
  exit 77
fi
check '[ $rc -eq 0 ] && [ "$(count "$dir/orbit")" -eq 8 ]' "orbit: 8 frames (rc $rc: $(tail -2 "$dir/log.txt"))"
check 'grep -q "animate: frame 1/8 (12%), .* s/frame, ETA 0m0[0-9]s" "$dir/log.txt"' "progress with ETA on stderr"
check 'grep -q "^loop$" "$dir/orbit.campath" && [ "$(grep -c "^time " "$dir/orbit.campath")" -eq 181 ]' "--save-path: a loop of 181 keys"
# without -o: the path only (also without the renderer: tests/cli_animate_path.sh), the same bytes
"$bin" animate "$dir/box.ply" --orbit --duration 2 --fps 4 --style sketchy --outline on --save-path "$dir/only.campath" $A
check '[ $? -eq 0 ] && cmp -s "$dir/only.campath" "$dir/orbit.campath" && [ "$(count "$dir")" -eq 0 ]' "--save-path without -o: the same path, no frames"
# frame k equals render --camera-at k/fps (same pixels), sketchy and points
for k in 0 3 5; do
  t=$(awk -v k=$k 'BEGIN { printf "%.17g", k / 4 }')
  "$bin" render "$dir/box.ply" -o "$dir/at$k.png" --camera-path "$dir/orbit.campath" --camera-at "$t" --style sketchy --outline on $A
  check '[ $? -eq 0 ] && cmp -s "$dir/at$k.png" "$dir/orbit/$(printf "frame-%05d.png" $k)"' "frame $k equals render --camera-at $t"
done
check '! cmp -s "$dir/orbit/frame-00000.png" "$dir/orbit/frame-00001.png"' "the camera moves between frames"

# a path file: three keys at uneven times, fov changing; frames at the key times are the keys
cat > "$dir/keys.campath" <<'EOF'
# three keys around the box
time 0
eye 5123457.3 4012343.0 252.0
target 5123457.3 4012346.0 250.4
fov 40
time 1.5     # up and fov carry over
eye 5123459.8 4012345.9 251.5
target 5123457.3 4012346.0 250.4
time 2
eye 5123457.3 4012348.9 252.5
target 5123457.3 4012346.0 250.4
up 0 0 1
fov 55
EOF
"$bin" animate "$dir/box.ply" -o "$dir/keys/" --camera-path "$dir/keys.campath" --fps 4 $A
check '[ $? -eq 0 ] && [ "$(count "$dir/keys")" -eq 9 ]' "path file: 2 s at 4 fps, open: 9 frames"
printf 'eye 5123459.8 4012345.9 251.5\ntarget 5123457.3 4012346.0 250.4\nfov 40\n' > "$dir/key1.cam"
"$bin" render "$dir/box.ply" -o "$dir/key1.png" --camera "$dir/key1.cam" $A
check 'cmp -s "$dir/key1.png" "$dir/keys/frame-00006.png"' "frame 6 (t = 1.5) is the key's camera file rendered"

# stopped and resumed equals uninterrupted: 40 frames, killed after the third frame is written
"$bin" animate "$dir/box.ply" -o "$dir/full/" --orbit --degrees 40 --duration 4 --fps 10 $A
check '[ $? -eq 0 ] && [ "$(count "$dir/full")" -eq 41 ]' "uninterrupted: 41 frames"
"$bin" animate "$dir/box.ply" -o "$dir/resumed/" --orbit --degrees 40 --duration 4 --fps 10 $A &
pid=$!
for ((w = 0; w < 600; w++)); do [ -e "$dir/resumed/frame-00002.png" ] && break; sleep 0.01; done
kill -TERM $pid 2> /dev/null; wait $pid 2> /dev/null
stopped=$(count "$dir/resumed")
check '[ -z "$(ls -A "$dir/resumed" | grep "\.part$")" ]' "a stopped run leaves no temporary frame"
"$bin" animate "$dir/box.ply" -o "$dir/resumed/" --orbit --degrees 40 --duration 4 --fps 10 --size 160x120 2> "$dir/resume.txt"
check '[ $? -eq 0 ] && same_frames "$dir/full" "$dir/resumed" 41' "stopped after $stopped frames and resumed: the same 41 frames"
check 'grep -q "complete ones kept" "$dir/resume.txt"' "the resumed run says how many frames it kept"
# missing and cut frames are made again, complete ones kept
rm "$dir/resumed/frame-00005.png"; head -c 100 "$dir/full/frame-00007.png" > "$dir/resumed/frame-00007.png"
"$bin" animate "$dir/box.ply" -o "$dir/resumed/" --orbit --degrees 40 --duration 4 --fps 10 --size 160x120 2> "$dir/resume2.txt"
check '[ $? -eq 0 ] && same_frames "$dir/full" "$dir/resumed" 41 && grep -q "(2 rendered, 39 complete ones kept)" "$dir/resume2.txt"' \
      "a missing and a cut frame are rendered again, the others kept"
# other settings into the same folder: refused
"$bin" animate "$dir/box.ply" -o "$dir/resumed/" --orbit --degrees 40 --duration 4 --fps 10 --style stipple $A 2> "$dir/mix.txt"
check '[ $? -eq 1 ] && grep -q "holds frames of another animation" "$dir/mix.txt"' "frames of other settings are not mixed in"

# a flyover: 1 s at 6 fps, open: 7 frames, each different
"$bin" animate "$dir/box.ply" -o "$dir/fly/" --flyover --duration 1 --fps 6 $A
check '[ $? -eq 0 ] && [ "$(count "$dir/fly")" -eq 7 ] && ! cmp -s "$dir/fly/frame-00000.png" "$dir/fly/frame-00006.png"' "flyover: 7 frames"

# ffmpeg missing (PATH without it): a clear error, the frames kept
mkdir -p "$dir/nobin"
PATH="$dir/nobin" "$bin" animate "$dir/box.ply" -o "$dir/nov.mp4" --orbit --duration 1 --fps 4 $A 2> "$dir/noff.txt"
rc=$?
check '[ $rc -eq 1 ] && grep -q "cannot make .*nov.mp4: ffmpeg is not on PATH" "$dir/noff.txt" && [ "$(count "$dir/nov.frames")" -eq 4 ] && [ ! -e "$dir/nov.mp4" ]' \
      "ffmpeg missing: exit 1, a clear error, the 4 frames kept in nov.frames (rc $rc: $(cat "$dir/noff.txt"))"
# the video, when this machine has ffmpeg
if command -v ffmpeg > /dev/null 2>&1; then
  "$bin" animate "$dir/box.ply" -o "$dir/nov.mp4" --orbit --duration 1 --fps 4 $A
  check '[ $? -eq 0 ] && [ -s "$dir/nov.mp4" ] && [ ! -e "$dir/nov.frames" ]' "with ffmpeg: the video, the frames removed"
  if command -v ffprobe > /dev/null 2>&1; then
    n=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames,width,height -of csv=p=0 "$dir/nov.mp4")
    check '[ "$n" = "160,120,4" ]' "the video is 160x120 with 4 frames (got $n)"
  fi
  "$bin" animate "$dir/box.ply" -o "$dir/kept.mp4" --orbit --duration 1 --fps 4 --keep-frames $A
  check '[ $? -eq 0 ] && [ -s "$dir/kept.mp4" ] && [ "$(count "$dir/kept.frames")" -eq 4 ]' "--keep-frames keeps them"
else
  echo "cli_animate: ffmpeg not installed: the video test is skipped (the missing-ffmpeg test ran)" >&2
fi

# usage errors: 2
printf 'time 0\neye 0 0 1\ntarget 0 0 0\nup 0 1 0\ntime 0\neye 1 0 1\ntarget 0 0 0\n' > "$dir/bad.campath"
for args in "" "$dir/box.ply -o $dir/u/" "$dir/box.ply -o $dir/u/ --orbit --flyover" "$dir/box.ply -o $dir/u.avi --orbit" \
            "$dir/box.ply -o $dir/u/ --flyover --degrees 90" "$dir/box.ply -o $dir/u/ --orbit --fps 0" \
            "$dir/box.ply -o $dir/u/ --camera-path $dir/keys.campath --duration 3" "$dir/box.ply -o $dir/u/ --orbit --style oil" \
            "$dir/box.ply -o $dir/u/ --camera-path $dir/bad.campath"; do
  "$bin" animate $args > /dev/null 2>&1
  rc=$?
  check '[ $rc -eq 2 ]' "usage error exits 2: animate $args (got $rc)"
done
"$bin" animate "$dir/box.ply" -o "$dir/u/" --camera-path "$dir/bad.campath" 2> "$dir/bad.txt"
check 'grep -q "bad.campath:5: time 0 is not after the previous key.s time 0" "$dir/bad.txt"' "a bad path file names FILE:LINE ($(cat "$dir/bad.txt"))"
"$bin" render "$dir/box.ply" -o "$dir/x.png" --camera-at 1 $A 2> "$dir/bad2.txt"
check '[ $? -eq 2 ] && grep -q -- "--camera-at needs --camera-path" "$dir/bad2.txt"' "render --camera-at without a path is a usage error"
"$bin" render "$dir/box.ply" -o "$dir/x.png" --camera-path "$dir/bad.campath" $A 2> "$dir/bad3.txt"
check '[ $? -eq 2 ] && grep -q "bad.campath:5:" "$dir/bad3.txt"' "render --camera-path with a bad file names FILE:LINE"
exit $fail
