#!/usr/bin/env bash
# Outputs never destroy data, end to end (docs/security.md): the output kind is checked before any
# work, an input is never overwritten, planted links at temporary names are not followed, special
# files are written through, "-" is standard output, a full disk is named as such. Everything
# happens on files this test creates in its own folder.
#   bash cli_output.sh /path/to/pointnpr SCRATCH_DIR
set -uo pipefail
bin=$1
dir=$2/cli_output
rm -rf "$dir"; mkdir -p "$dir"
. "$(dirname "$0")/lib_cli.sh"
sum() { md5sum "$1" | cut -d' ' -f1; }

cube_ply "$dir/cube.ply"
orig=$(sum "$dir/cube.ply")
has_render=1 # the render checks only with the renderer
built_with_render "$bin" || has_render=0

# 4. an output that is the input (also through a link or a hard link), or of the wrong kind
if [ $has_render = 1 ]; then
  "$bin" render "$dir/cube.ply" -o "$dir/cube.ply" --quiet 2> "$dir/e1.txt"; rc=$?
  check '[ $rc -eq 2 ] && grep -q "must end in .png" "$dir/e1.txt"' "render -o IN.ply refused as a usage error (rc $rc)"
fi
"$bin" lines "$dir/cube.ply" -o "$dir/cube.ply" --quiet 2> "$dir/e2.txt"; rc=$?
check '[ $rc -eq 1 ] && grep -q "is the input" "$dir/e2.txt"' "lines -o IN.ply refused (rc $rc)"
"$bin" features "$dir/cube.ply" -o "$dir/cube.ply" --quiet 2> "$dir/e3.txt"; rc=$?
check '[ $rc -eq 1 ] && grep -q "is the input" "$dir/e3.txt"' "features -o IN refused (rc $rc)"
ln -s cube.ply "$dir/alias.ply"; ln "$dir/cube.ply" "$dir/hard.ply"
"$bin" segment "$dir/cube.ply" -o "$dir/alias.ply" --quiet 2>/dev/null; rc1=$?
"$bin" convert "$dir/cube.ply" -o "$dir/hard.ply" --quiet 2>/dev/null; rc2=$?
check '[ $rc1 -eq 1 ] && [ $rc2 -eq 1 ]' "an output that is the input through a link is refused ($rc1 $rc2)"
"$bin" features "$dir/cube.ply" -o "$dir/out.png" --quiet 2> "$dir/e4.txt"; rc=$?
check '[ $rc -eq 2 ] && grep -q "must end in .ply or .pcd" "$dir/e4.txt"' "features -o x.png refused (rc $rc)"
check '[ "$(sum "$dir/cube.ply")" = "$orig" ]' "the input is unchanged after every refusal"

# output folder missing: refused before the work starts (no 'computing' stage runs)
for c in features segment lines; do
  "$bin" $c "$dir/cube.ply" -o "$dir/missing/out.ply" 2> "$dir/e5.txt"; rc=$?
  check '[ $rc -eq 1 ] && grep -q "cannot write into the folder" "$dir/e5.txt" && ! grep -q "done" "$dir/e5.txt"' \
        "$c: a missing output folder is refused before any work (rc $rc)"
done

# 2. links planted at the names earlier versions used for temporaries, and a user's own OUT.tmp
echo victim > "$dir/victim"; echo mine > "$dir/out.ply.tmp"
ln -s victim "$dir/img.png.tmp-png"; ln -s victim "$dir/lines.obj.tmp"
"$bin" features "$dir/cube.ply" -o "$dir/out.ply" --quiet; rc1=$?
"$bin" lines "$dir/cube.ply" -o "$dir/lines.obj" --quiet 2>/dev/null; rc2=$?
check '[ $rc1 -eq 0 ] && [ $rc2 -eq 0 ]' "writes next to planted names succeed ($rc1 $rc2)"
check '[ "$(cat "$dir/victim")" = victim ] && [ "$(cat "$dir/out.ply.tmp")" = mine ]' "planted links and OUT.tmp untouched"
check '[ -z "$(ls -A "$dir" | grep "\.part$")" ]' "no temporary left"

# a link to a regular file: the file is replaced, the link stays
cp "$dir/out.ply" "$dir/target.ply"; ln -s target.ply "$dir/via.ply"
"$bin" convert "$dir/cube.ply" -o "$dir/via.ply" --ascii --quiet
check '[ -L "$dir/via.ply" ] && head -2 "$dir/target.ply" | grep -q ascii' "a link's target is replaced, the link kept"
# a dangling link is refused and its target not created
ln -s nothing.ply "$dir/dangling.ply"
"$bin" features "$dir/cube.ply" -o "$dir/dangling.ply" --quiet 2> "$dir/e6.txt"; rc=$?
check '[ $rc -eq 1 ] && [ ! -e "$dir/nothing.ply" ] && grep -q "link to nothing" "$dir/e6.txt"' "a dangling link is refused (rc $rc)"

# 3. special files: written through, never replaced
mkfifo "$dir/pipe"
timeout 60 cat "$dir/pipe" > "$dir/from-pipe.ply" &
reader=$!
timeout 60 "$bin" features "$dir/cube.ply" -o "$dir/pipe" --quiet; rc=$?
wait $reader
check '[ $rc -eq 0 ] && [ -p "$dir/pipe" ] && "$bin" info "$dir/from-pipe.ply" | grep -q feature_degree' "a FIFO is written through (rc $rc)"
if [ $has_render = 1 ]; then
  "$bin" render "$dir/cube.ply" -o /dev/null --quiet --size 64x48; rc=$?
  check '[ $rc -eq 0 ] && [ -c /dev/null ]' "/dev/null is written through and stays a device (rc $rc)"
fi
if [ -c /dev/full ]; then
  "$bin" features "$dir/cube.ply" -o /dev/full --quiet 2> "$dir/e7.txt"; rc=$?
  check '[ $rc -eq 1 ] && grep -q "No space left on device" "$dir/e7.txt"' "a full device is named as such (rc $rc)"
  if [ $has_render = 1 ]; then
    "$bin" render "$dir/cube.ply" -o /dev/full --quiet --size 64x48 2> "$dir/e8.txt"; rc=$?
    check '[ $rc -eq 1 ] && grep -q "No space left on device" "$dir/e8.txt"' "render: a full device is named as such (rc $rc)"
  fi
fi

# "-": standard output
"$bin" features "$dir/cube.ply" -o - --quiet > "$dir/stdout.ply"; rc=$?
check '[ $rc -eq 0 ] && head -c 4 "$dir/stdout.ply" | grep -q ply' "features -o - writes PLY to standard output"
check '"$bin" info "$dir/stdout.ply" | grep -q "feature_degree"' "the PLY from standard output reads back with its properties"
if [ $has_render = 1 ]; then
  "$bin" render "$dir/cube.ply" -o - --quiet --size 64x48 > "$dir/stdout.png"; rc=$?
  check '[ $rc -eq 0 ] && [ "$(head -c 4 "$dir/stdout.png" | tail -c 3)" = PNG ]' "render -o - writes a PNG to standard output"
fi
"$bin" lines "$dir/cube.ply" -o - --quiet > "$dir/stdout.obj" 2>/dev/null; rc=$?
check '[ $rc -eq 0 ] && head -1 "$dir/stdout.obj" | grep -q "^# profile lines" && cmp -s "$dir/stdout.obj" "$dir/lines.obj"' \
      "lines -o - writes the same OBJ to standard output as to a file"
"$bin" lines "$dir/cube.ply" -o - --svg - --quiet > /dev/null 2>&1; rc=$?
check '[ $rc -eq 2 ]' "lines: -o and --svg cannot both be standard output (rc $rc)"
check '[ -z "$(ls -A "$dir" | grep "\.part$")" ]' "no temporary left at the end"
check '[ "$(sum "$dir/cube.ply")" = "$orig" ]' "the input is unchanged at the end"

exit $fail
