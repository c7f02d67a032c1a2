#!/usr/bin/env bash
# Text point clouds and OFF as real tools write them, from the command line: info on XYZ / PTS /
# CSV (format, count, colours, normals, properties), --columns on info and convert, coordinates
# written back exactly (5e6 + millimetres), errors that name the file and the line, usage errors.
# Usage: bash cli_text.sh /path/to/pointnpr SCRATCH_DIR
set -euo pipefail

if [[ $# -ne 2 ]]; then
  echo "usage: bash cli_text.sh /path/to/pointnpr SCRATCH_DIR" >&2
  exit 2
fi
BIN=$1
DIR=$2/cli_text
rm -rf "$DIR"
mkdir -p "$DIR"

failures=0
fail() { echo "cli_text: FAIL: $*" >&2; failures=$((failures + 1)); }
info_field() { "$BIN" info "$@" | sed -n "s/^$FIELD: *//p"; }
expect() { # FIELD WANT ARGS...: `pointnpr info ARGS` prints WANT for FIELD
  local field=$1 want=$2 got
  shift 2
  got=$(FIELD=$field info_field "$@") || true
  [[ "$got" == "$want" ]] || fail "info $*: $field '$got', want '$want'"
}

printf '# georeferenced\r\n5000000.123 5000000.456 100.789\r\n5000001.001\t5000000.002 100.5\r\n' > "$DIR/geo.xyz"
expect format "XYZ (from the extension)" "$DIR/geo.xyz"
expect points 2 "$DIR/geo.xyz"
expect "source xyz" "exact, kept as double" "$DIR/geo.xyz"
"$BIN" convert "$DIR/geo.xyz" -o "$DIR/geo.ply" --ascii --quiet
grep -qx "5000001.001 5000000.002 100.5" "$DIR/geo.ply" || fail "convert geo.xyz: the second point is not written back exactly"

printf '2\n1 2 3 -5 10 20 30\n4 5 6 7 40 50 60\n' > "$DIR/scan.pts"
expect points 2 "$DIR/scan.pts"
expect colour "yes (8-bit RGB)" "$DIR/scan.pts"
expect properties "intensity (double)" "$DIR/scan.pts"

printf 'id;east;north;height\n1;10.5;20.5;1.25\n2;11;21;2\n' > "$DIR/survey.csv"
"$BIN" info "$DIR/survey.csv" > /dev/null 2> "$DIR/err.txt" && fail "survey.csv without --columns read"
grep -q "survey.csv: line 1: the columns (header) have no x column" "$DIR/err.txt" || fail "header message: $(cat "$DIR/err.txt")"
expect points 2 "$DIR/survey.csv" --columns _,x,y,z
expect "bbox max" "11.000 21.000 2.000" "$DIR/survey.csv" --columns _,x,y,z
"$BIN" convert "$DIR/survey.csv" --columns id,x,y,z -o "$DIR/survey.ply" --quiet
expect properties "id (double)" "$DIR/survey.ply"

printf '1 2 3\n4 5\n' > "$DIR/bad.xyz"
"$BIN" info "$DIR/bad.xyz" > /dev/null 2> "$DIR/err.txt" && fail "bad.xyz read"
grep -q "bad.xyz: line 2: 2 values, the columns give 3" "$DIR/err.txt" || fail "bad.xyz message: $(cat "$DIR/err.txt")"

rc=0
"$BIN" info "$DIR/geo.xyz" --columns x,y > /dev/null 2>&1 || rc=$?
[[ $rc -eq 2 ]] || fail "--columns x,y: exit $rc, want 2"

# OFF with comments before the keyword and after colours (CGAL's mesh_with_colors.off)
printf '# a comment\nCOFF\n3 1 0\n0 0 0 0.9 0 0 #red\n1 0 0 0 0 0.9 # blue\n0 1 0 0 0.9 0\n3 0 1 2 0.9 0 0 #face\n' > "$DIR/c.off"
expect points 3 "$DIR/c.off"
expect colour "yes (8-bit RGB)" "$DIR/c.off"
expect faces 1 "$DIR/c.off"

if [[ $failures -ne 0 ]]; then
  echo "cli_text: $failures failure(s)" >&2
  exit 1
fi
echo "cli_text: all checks passed"
