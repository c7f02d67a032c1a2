#!/usr/bin/env bash
# Conformance on a public corpus none of us wrote: every OFF, PLY, OBJ, XYZ and PWN file of CGAL
# 5.5's data folder (Debian's libcgal-demo 5.5.1-2, 172 files from many tools) must read with
# `pointnpr info`, with the point count an independent reader gives: the file's own header (OFF,
# PLY), or its data lines (XYZ, PWN; OBJ: its 'v' lines). For the text formats (OFF, XYZ, PWN)
# the first and last point written back by `pointnpr convert --ascii` must equal the file's text
# (as doubles). The files are checked against tests/conformance/cgal-5.5.1-2-data.sha256 first.
#
# Usage: bash conformance.sh /path/to/pointnpr SCRATCH_DIR
# Exit 0: all read and agree; 1: a file was refused or disagrees; 77 (CTest SKIP_RETURN_CODE):
# libcgal-demo 5.5.1-2 is not installed (packaging/install-deps.sh installs it).
# Writes SCRATCH_DIR/conformance/table.md (one row per file; docs/io.md has the summary).
set -euo pipefail

if [[ $# -ne 2 ]]; then
  echo "usage: bash conformance.sh /path/to/pointnpr SCRATCH_DIR" >&2
  exit 2
fi
BIN=$1
DIR=$2/conformance
HERE=$(cd "$(dirname "$0")" && pwd)
MANIFEST=$HERE/conformance/cgal-5.5.1-2-data.sha256
PINNED=5.5.1-2

version=$(dpkg-query -W -f='${Status} ${Version}' libcgal-demo 2>/dev/null || true)
TARBALL=""
for t in /usr/share/doc/libcgal-demo/data.tar.gz /usr/share/doc/libcgal-dev/data.tar.gz; do
  [[ -f "$t" ]] && { TARBALL=$t; break; }
done
if [[ "$version" != "install ok installed $PINNED" || -z "$TARBALL" ]]; then
  echo "conformance: SKIPPED: the corpus package libcgal-demo $PINNED is not installed" \
       "(found: '${version:-nothing}'); packaging/install-deps.sh installs it" >&2
  exit 77
fi

# Extract once; the manifest decides whether the extracted copy is the pinned corpus.
mkdir -p "$DIR"
if ! (cd "$DIR" && sha256sum --quiet -c "$MANIFEST" > /dev/null 2>&1); then
  rm -rf "$DIR/data"
  tar -xzf "$TARBALL" -C "$DIR" data
  if ! (cd "$DIR" && sha256sum --quiet -c "$MANIFEST"); then
    echo "conformance: FAIL: the files of $TARBALL differ from $MANIFEST" >&2
    exit 1
  fi
fi

# The independent reader: the point count the file itself states or holds.
expected_count() {
  local f=$1
  case "${f,,}" in
    *.ply) LC_ALL=C awk '/^end_header/ {exit} $1 == "element" && $2 == "vertex" {sub(/\r$/, "", $3); print $3; exit}' "$f" ;;
    *.off) LC_ALL=C awk '{sub(/#.*/, "")} {for (i = 1; i <= NF; i++) { if (++k == 2) {print $i; exit} }}' "$f" ;;
    *.obj) LC_ALL=C awk '$1 == "v" {n++} END {print n + 0}' "$f" ;;
    *) LC_ALL=C awk '{sub(/#.*/, "")} NF >= 3 {n++} END {print n + 0}' "$f" ;;
  esac
}

# The first and last point of a text file as "x y z|x y z" (OFF: the vertex lines that follow the
# counts, one vertex a line as every file of the corpus writes them; XYZ/PWN: the data lines).
text_ends() {
  case "${1,,}" in
    *.off) LC_ALL=C awk '{sub(/#.*/, "")} NF == 0 {next}
             k < 4 {for (i = 1; i <= NF && k < 4; i++) {k++; if (k == 2) nv = $i}; next}
             v < nv {v++; p = $1 " " $2 " " $3; if (v == 1) first = p; last = p}
             END {print first "|" last}' "$1" ;;
    *) LC_ALL=C awk '{sub(/#.*/, "")} NF >= 3 {p = $1 " " $2 " " $3; if (!n++) first = p; last = p}
             END {print first "|" last}' "$1" ;;
  esac
}

# The same from pointnpr's ascii PLY: the first and the last vertex line.
ours_ends() {
  "$BIN" convert "$1" -o - --ascii --quiet 2> /dev/null | LC_ALL=C awk '
    !body && $1 == "element" && $2 == "vertex" {nv = $3}
    !body && /^end_header/ {body = 1; next}
    body && ++v <= nv {p = $1 " " $2 " " $3; if (v == 1) first = p; last = p}
    END {print first "|" last}'
}

same_numbers() { # "a b c|d e f" twice: equal as doubles
  LC_ALL=C awk -v a="$1" -v b="$2" 'BEGIN {
    na = split(a, x, /[ |]/); nb = split(b, y, /[ |]/); ok = na == nb && na == 6
    for (i = 1; ok && i <= na; i++) ok = (x[i] + 0 == y[i] + 0)
    exit !ok }'
}

table=$DIR/table.md
echo "| file | format | points (independent) | points (pointnpr) | result |" > "$table"
echo "|---|---|---|---|---|" >> "$table"
total=0 read_ok=0 failures=0
while read -r _ rel; do
  f=$DIR/$rel
  total=$((total + 1))
  want=$(expected_count "$f")
  if ! out=$("$BIN" info "$f" 2>&1); then
    why=$(echo "$out" | head -1)
    echo "| $rel | ${rel##*.} | $want | - | refused: ${why//|/\\|} |" >> "$table"
    echo "conformance: FAIL: $rel refused: $why" >&2
    failures=$((failures + 1))
    continue
  fi
  got=$(echo "$out" | sed -n 's/^points: *//p')
  result="read"
  if [[ "$got" != "$want" ]]; then
    result="count differs"
  elif [[ "${rel,,}" =~ \.(off|xyz|pwn)$ ]] && [[ "$want" != 0 ]]; then
    theirs=$(text_ends "$f")
    ours=$(ours_ends "$f")
    same_numbers "$theirs" "$ours" || result="first/last point differs ($theirs vs $ours)"
    [[ "$result" == read ]] && result="read, first/last point equal"
  fi
  echo "| $rel | ${rel##*.} | $want | $got | $result |" >> "$table"
  if [[ "$result" == read* ]]; then
    read_ok=$((read_ok + 1))
  else
    echo "conformance: FAIL: $rel: $result (independent count $want, pointnpr $got)" >&2
    failures=$((failures + 1))
  fi
done < "$MANIFEST"

echo "conformance: CGAL $PINNED data: $read_ok of $total files read with the independent reader's counts" \
     "($failures failed); table: $table"
[[ $failures -eq 0 ]]
