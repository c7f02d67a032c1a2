#!/usr/bin/env bash
# PCD from the command line: info on an ascii PCD (format, NaN points, properties, viewpoint),
# convert PCD -> PLY -> PCD with identical data, a .pcd file found by its content, errors that
# name the file and the line, usage errors; and, when Debian's pcl-tools are installed, PCL
# itself reading what we write and writing binary_compressed that we read back identically.
# Usage: bash cli_pcd.sh /path/to/pointnpr SCRATCH_DIR
set -euo pipefail

if [[ $# -ne 2 ]]; then
  echo "usage: bash cli_pcd.sh /path/to/pointnpr SCRATCH_DIR" >&2
  exit 2
fi
BIN=$1
DIR=$2/cli_pcd
rm -rf "$DIR"
mkdir -p "$DIR"

failures=0
fail() { echo "cli_pcd: FAIL: $*" >&2; failures=$((failures + 1)); }
info_field() { "$BIN" info "$1" | sed -n "s/^$2: *//p"; }

# An organised 2x2 ascii cloud: rgb as PCL packs it (a float holding 0x00RRGGBB), a NaN hole,
# an extra field, a viewpoint.
cat > "$DIR/a.pcd" <<'PCD'
# .PCD v0.7 - Point Cloud Data file format
VERSION 0.7
FIELDS x y z rgb intensity
SIZE 4 4 4 4 2
TYPE F F F F U
COUNT 1 1 1 1 1
WIDTH 2
HEIGHT 2
VIEWPOINT 1 2 3 1 0 0 0
POINTS 4
DATA ascii
0 0 1 2.34180515e-38 7
1 0 1 2.34180515e-38 8
nan nan nan 0 0
1 1 1.5 9.14767638e-41 9
PCD

"$BIN" info "$DIR/a.pcd" > "$DIR/a.info" || fail "info a.pcd: $(cat "$DIR/a.info")"
grep -q '^format: *PCD (from the extension)' "$DIR/a.info" || fail "a.pcd format: $(cat "$DIR/a.info")"
grep -q '^points: *4$' "$DIR/a.info" || fail "a.pcd points: $(cat "$DIR/a.info")"
grep -q '^finite: *3 (1 points with NaN/Inf' "$DIR/a.info" || fail "a.pcd finite: $(cat "$DIR/a.info")"
grep -q '^colour: *yes' "$DIR/a.info" || fail "a.pcd colour: $(cat "$DIR/a.info")"
grep -q '^properties: *intensity (ushort)$' "$DIR/a.info" || fail "a.pcd properties: $(cat "$DIR/a.info")"
grep -q '^viewpoint: *1.000 2.000 3.000$' "$DIR/a.info" || fail "a.pcd viewpoint: $(cat "$DIR/a.info")"

# PCD -> PLY (ascii, to see the colours) -> PCD -> PLY: the same
"$BIN" convert "$DIR/a.pcd" -o "$DIR/a.ply" --ascii --quiet || fail "convert a.pcd -> a.ply"
grep -q '^0 0 1 255 0 0 7$' "$DIR/a.ply" || fail "a.ply first point (rgb 0x00FF0000): $(grep -A1 end_header "$DIR/a.ply")"
grep -q '^1 1 1.5 0 255 0 9$' "$DIR/a.ply" || fail "a.ply last point (rgb 0x0000FF00): $(tail -n 1 "$DIR/a.ply")"
"$BIN" convert "$DIR/a.ply" -o "$DIR/b.pcd" --quiet || fail "convert a.ply -> b.pcd"
head -c 400 "$DIR/b.pcd" | grep -q '^DATA binary$' || fail "b.pcd is not binary PCD"
cp "$DIR/b.pcd" "$DIR/b_noext"
"$BIN" convert "$DIR/b_noext" -o "$DIR/b.ply" --ascii --quiet || fail "convert b_noext (PCD by content)"
cmp -s <(grep -v '^comment' "$DIR/a.ply") <(grep -v '^comment' "$DIR/b.ply") || fail "a.ply and b.ply differ"
[[ "$(info_field "$DIR/b_noext" format)" == "PCD (from the content)" ]] || fail "b_noext: $(info_field "$DIR/b_noext" format)"

# errors name the file and the line; nothing is written
printf 'VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F Q F\nPOINTS 1\nDATA ascii\n1 2 3\n' > "$DIR/bad.pcd"
if "$BIN" convert "$DIR/bad.pcd" -o "$DIR/bad.ply" > "$DIR/bad.log" 2>&1; then fail "bad.pcd was accepted"; fi
grep -q "bad.pcd: line 4: TYPE 'Q' of field 'y' is unknown" "$DIR/bad.log" || fail "bad.pcd message: $(cat "$DIR/bad.log")"
[[ ! -e "$DIR/bad.ply" ]] || fail "bad.ply was written"
set +e
"$BIN" convert "$DIR/a.pcd" -o "$DIR/c.pcd" --ascii > "$DIR/usage.log" 2>&1
rc=$?
set -e
[[ $rc -eq 2 ]] || fail "--ascii with a .pcd output: exit $rc, expected 2"
grep -q 'PCD is written binary only' "$DIR/usage.log" || fail "--ascii .pcd message: $(cat "$DIR/usage.log")"

# PCL itself, when installed (Debian package pcl-tools; not a dependency of the project)
if command -v pcl_convert_pcd_ascii_binary > /dev/null 2>&1; then
  for mode in 0 1 2; do
    if ! pcl_convert_pcd_ascii_binary "$DIR/b.pcd" "$DIR/pcl_$mode.pcd" "$mode" > "$DIR/pcl_$mode.log" 2>&1; then
      fail "PCL cannot read our b.pcd (mode $mode): $(tail -n 2 "$DIR/pcl_$mode.log")"
      continue
    fi
    "$BIN" convert "$DIR/pcl_$mode.pcd" -o "$DIR/pcl_$mode.ply" --ascii --quiet || fail "PCL's mode $mode output does not read"
    cmp -s <(grep -v '^comment' "$DIR/a.ply") <(grep -v '^comment' "$DIR/pcl_$mode.ply") ||
      fail "PCL's mode $mode output reads differently"
  done
else
  echo "cli_pcd: pcl-tools not installed: the checks against PCL are skipped" >&2
fi

if [[ $failures -ne 0 ]]; then
  echo "cli_pcd: $failures failure(s)" >&2
  exit 1
fi
echo "cli_pcd: all checks passed" >&2
