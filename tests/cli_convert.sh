#!/usr/bin/env bash
# pointnpr convert / info from the command line: merging PLY and LAS inputs, a directory as
# input, exact LAS coordinates in the output, failures that name the input and write nothing,
# usage errors.  Usage: bash cli_convert.sh /path/to/pointnpr SCRATCH_DIR
set -euo pipefail

if [[ $# -ne 2 ]]; then
  echo "usage: bash cli_convert.sh /path/to/pointnpr SCRATCH_DIR" >&2
  exit 2
fi
BIN=$1
DIR=$2/cli_convert
rm -rf "$DIR"
mkdir -p "$DIR/tiles"

failures=0
fail() { echo "cli_convert: FAIL: $*" >&2; failures=$((failures + 1)); }

# --- inputs --------------------------------------------------------------------------------
ply_header() { # $1 = vertex count
  printf 'ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n' "$1"
  printf 'property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n'
}
{ ply_header 3; printf '0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n'; } > "$DIR/a.ply"
{ ply_header 2; printf '0 0 1 10 20 30\n1 1 1 40 50 60\n'; } > "$DIR/b.ply"

# Little-endian integers and a LAS 1.2 point format 2 file, written with printf only.
le16() { printf "\\x$(printf %02x $(($1 & 255)))\\x$(printf %02x $((($1 >> 8) & 255)))"; }
le32() { le16 $(($1 & 65535)); le16 $((($1 >> 16) & 65535)); }
zeros() { head -c "$1" /dev/zero; }
SCALE_0001='\xfc\xa9\xf1\xd2\x4d\x62\x50\x3f' # 0.001
OFFSET_5E6='\x00\x00\x00\x00\xd0\x12\x53\x41' # 5000000.0
# make_las FILE X Y Z R G B [X Y Z R G B ...]  (scale 0.001; offset 5e6, 5e6, 0)
make_las() {
  local file=$1
  shift
  local n=$(($# / 6))
  {
    printf 'LASF'; zeros 4; zeros 16; printf '\x01\x02'; zeros 64; zeros 4
    le16 227; le32 227; le32 0; printf '\x02'; le16 26; le32 "$n"; zeros 20
    printf "$SCALE_0001$SCALE_0001$SCALE_0001"
    printf "$OFFSET_5E6$OFFSET_5E6"; zeros 8
    zeros 48
    while [[ $# -ge 6 ]]; do
      le32 "$1"; le32 "$2"; le32 "$3"
      le16 100; printf '\x00\x02\x00\x00'; le16 0 # intensity, flags, class 2, scan angle, user, source id
      le16 "$4"; le16 "$5"; le16 "$6"
      shift 6
    done
  } > "$file"
}
make_las "$DIR/c.las" 1 2 3 65535 0 0  1000 -2000 0 0 65535 32768
make_las "$DIR/tiles/t1.las" 0 0 0 255 0 0  10 10 10 0 255 0
make_las "$DIR/tiles/t2.las" 20 20 20 0 0 255
cp "$DIR/a.ply" "$DIR/tiles/t0.ply"
echo "not a point cloud" > "$DIR/tiles/readme.txt"
printf 'LASX' > "$DIR/bad.las"; zeros 300 >> "$DIR/bad.las"

info_field() { # $1 file, $2 field name -> value
  "$BIN" info "$1" | sed -n "s/^$2: *//p"
}

# --- merging files of several formats -------------------------------------------------------
if "$BIN" convert "$DIR/a.ply" "$DIR/b.ply" "$DIR/c.las" -o "$DIR/merged.ply" 2> "$DIR/merged.log"; then
  [[ "$(info_field "$DIR/merged.ply" points)" == 7 ]] || fail "merged.ply: expected 7 points, info says: $("$BIN" info "$DIR/merged.ply")"
  [[ "$(info_field "$DIR/merged.ply" colour)" == yes* ]] || fail "merged.ply has no colour"
  grep -q "read 3/3: $DIR/c.las (2 points)" "$DIR/merged.log" || fail "no 'read 3/3' line: $(cat "$DIR/merged.log")"
  grep -q "wrote $DIR/merged.ply: 7 points" "$DIR/merged.log" || fail "no 'wrote' line: $(cat "$DIR/merged.log")"
else
  fail "convert a.ply b.ply c.las exited $?: $(cat "$DIR/merged.log")"
fi

# --- LAS alone: exact world coordinates, properties -----------------------------------------
if "$BIN" info "$DIR/c.las" > "$DIR/c.info" 2>&1; then
  grep -q '^format: *LAS' "$DIR/c.info" || fail "c.las: format: $(cat "$DIR/c.info")"
  grep -q '^bbox min: *5000000.001 4999998.000 0.000$' "$DIR/c.info" || fail "c.las bbox min: $(cat "$DIR/c.info")"
  grep -q '^bbox max: *5000001.000 5000000.002 0.003$' "$DIR/c.info" || fail "c.las bbox max: $(cat "$DIR/c.info")"
  grep -q 'intensity (ushort), classification (uchar)' "$DIR/c.info" || fail "c.las properties: $(cat "$DIR/c.info")"
else
  fail "info c.las failed: $(cat "$DIR/c.info")"
fi
if "$BIN" convert "$DIR/c.las" -o "$DIR/c.ply" --ascii 2> "$DIR/c.log"; then
  head -c 200 "$DIR/c.ply" | grep -q 'format ascii 1.0' || fail "c.ply is not ascii"
  "$BIN" info "$DIR/c.ply" > "$DIR/c.ply.info"
  grep -q '^bbox min: *5000000.001 4999998.000 0.000$' "$DIR/c.ply.info" || fail "c.ply bbox: $(cat "$DIR/c.ply.info")"
  grep -q 'intensity (ushort), classification (uchar)' "$DIR/c.ply.info" || fail "c.ply properties lost: $(cat "$DIR/c.ply.info")"
else
  fail "convert c.las --ascii failed: $(cat "$DIR/c.log")"
fi

# --- a directory as input (supported files only, sorted) ------------------------------------
if "$BIN" convert "$DIR/tiles" -o "$DIR/tiles.ply" --big-endian 2> "$DIR/tiles.log"; then
  [[ "$(info_field "$DIR/tiles.ply" points)" == 6 ]] || fail "tiles.ply: expected 6 points: $("$BIN" info "$DIR/tiles.ply")"
  grep -q "read 1/3: $DIR/tiles/t0.ply (3 points)" "$DIR/tiles.log" || fail "directory order: $(cat "$DIR/tiles.log")"
  grep -q "read 3/3: $DIR/tiles/t2.las (1 points)" "$DIR/tiles.log" || fail "directory order: $(cat "$DIR/tiles.log")"
  head -c 200 "$DIR/tiles.ply" | grep -q 'binary_big_endian' || fail "tiles.ply is not big endian"
else
  fail "convert DIR exited $?: $(cat "$DIR/tiles.log")"
fi

# --- a bad input: exit 1, its name on stderr, no output (and an existing output untouched) ---
set +e
"$BIN" convert "$DIR/a.ply" "$DIR/bad.las" -o "$DIR/never.ply" 2> "$DIR/bad.log"
rc=$?
set -e
[[ $rc -eq 1 ]] || fail "corrupt input: exit $rc, expected 1"
grep -q "bad.las" "$DIR/bad.log" || fail "corrupt input not named on stderr: $(cat "$DIR/bad.log")"
[[ ! -e "$DIR/never.ply" ]] || fail "output written despite a bad input"

echo "sentinel" > "$DIR/keep.ply"
set +e
"$BIN" convert "$DIR/a.ply" "$DIR/missing.las" -o "$DIR/keep.ply" 2> "$DIR/missing.log"
rc=$?
set -e
[[ $rc -eq 1 ]] || fail "missing input: exit $rc, expected 1"
grep -q "missing.las: No such file or directory" "$DIR/missing.log" || fail "missing input message: $(cat "$DIR/missing.log")"
[[ "$(cat "$DIR/keep.ply")" == sentinel ]] || fail "existing output changed by a failed convert"
ls "$DIR" | grep -q partial && fail "temporary file left behind: $(ls "$DIR")"

# output into a directory that does not exist: exit 1, nothing created
set +e
"$BIN" convert "$DIR/a.ply" -o "$DIR/no/such/dir/out.ply" 2> "$DIR/nodir.log"
rc=$?
set -e
[[ $rc -eq 1 ]] || fail "unwritable output: exit $rc, expected 1 ($(cat "$DIR/nodir.log"))"

# --- usage errors: exit 2 -------------------------------------------------------------------
expect_rc() { # expected-rc description command...
  local want=$1 what=$2
  shift 2
  set +e
  "$@" > /dev/null 2> "$DIR/usage.log"
  local got=$?
  set -e
  [[ $got -eq $want ]] || fail "$what: exit $got, expected $want ($(cat "$DIR/usage.log"))"
}
expect_rc 2 "convert without arguments" "$BIN" convert
expect_rc 2 "convert without -o" "$BIN" convert "$DIR/a.ply"
expect_rc 2 "convert without input" "$BIN" convert -o "$DIR/x.ply"
expect_rc 2 "convert -o without a name" "$BIN" convert "$DIR/a.ply" -o
expect_rc 2 "convert unknown option" "$BIN" convert "$DIR/a.ply" -o "$DIR/x.ply" --frobnicate
expect_rc 2 "convert to .las" "$BIN" convert "$DIR/a.ply" -o "$DIR/x.las"
expect_rc 2 "convert two encodings" "$BIN" convert "$DIR/a.ply" -o "$DIR/x.ply" --ascii --big-endian
expect_rc 0 "convert --help" "$BIN" convert --help
expect_rc 2 "info without arguments" "$BIN" info
expect_rc 2 "info with two inputs" "$BIN" info "$DIR/a.ply" "$DIR/b.ply"
expect_rc 2 "info unknown option" "$BIN" info --frobnicate "$DIR/a.ply"
expect_rc 0 "info --help" "$BIN" info --help
expect_rc 1 "info of a bad file" "$BIN" info "$DIR/bad.las"
[[ ! -e "$DIR/x.ply" ]] || fail "a usage error wrote output"

if [[ $failures -ne 0 ]]; then
  echo "cli_convert: $failures failure(s)" >&2
  exit 1
fi
echo "cli_convert: all checks passed"
