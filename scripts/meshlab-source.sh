#!/usr/bin/env bash
# Unpacks the source of Debian's meshlab package (MeshLab 2020.09: src/ + the matching vcglib/)
# so that plugin/meshlab can be compiled against the host's own headers.
#
#   scripts/meshlab-source.sh BUILD_DIR
#
# - Enables a deb-src entry for bookworm when apt has none (a file
#   /etc/apt/sources.list.d/pointnpr-bookworm-src.sources with the same URIs/Suites/Components/
#   Signed-By as the existing deb entry), then runs apt-get update. Idempotent.
# - Runs `apt-get source meshlab` into BUILD_DIR/meshlab-src (cached: nothing is fetched when the
#   unpacked tree is already there).
# The last line on stdout is the unpacked source tree (the folder holding src/ and vcglib/);
# every message goes to stderr. Needs root (or sudo) only when the deb-src entry is missing.
set -euo pipefail

die() { echo "meshlab-source: $*" >&2; exit 1; }

if [[ $# -ne 1 || "$1" == "-h" || "$1" == "--help" ]]; then
  echo "usage: scripts/meshlab-source.sh BUILD_DIR   (prints the unpacked meshlab source tree)" >&2
  [[ $# -eq 1 ]] && exit 0
  exit 2
fi

mkdir -p "$1/meshlab-src" || die "cannot create $1/meshlab-src"
DEST=$(cd "$1/meshlab-src" && pwd)

find_tree() {
  local d
  for d in "$DEST"/meshlab-*/; do
    [[ -f "$d/src/common/interfaces.h" && -d "$d/vcglib/vcg" ]] && { echo "${d%/}"; return 0; }
  done
  return 1
}

if tree=$(find_tree); then
  echo "meshlab-source: using cached source in $tree" >&2
  echo "$tree"
  exit 0
fi

SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi

has_deb_src() {
  # one-line format (sources.list) or deb822 (*.sources)
  grep -qsE '^[[:space:]]*deb-src[[:space:]].*bookworm' /etc/apt/sources.list /etc/apt/sources.list.d/*.list && return 0
  local f
  for f in /etc/apt/sources.list.d/*.sources; do
    [[ -f "$f" ]] || continue
    awk 'BEGIN{RS=""} /Types:[^\n]*deb-src/ && /Suites:[^\n]*bookworm([ \t\n]|$)/ {found=1} END{exit !found}' "$f" && return 0
  done
  return 1
}

if ! has_deb_src; then
  src_file=/etc/apt/sources.list.d/pointnpr-bookworm-src.sources
  entry=""
  if [[ -f /etc/apt/sources.list.d/debian.sources ]]; then
    # Copy the stanza that serves bookworm (not -security), turning it into deb-src.
    entry=$(awk 'BEGIN{RS=""; ORS="\n\n"} /Suites:[^\n]*bookworm([ \t\n]|$)/ && /Types:[^\n]*deb/ {
                   sub(/Types:[^\n]*/, "Types: deb-src"); print; exit }' /etc/apt/sources.list.d/debian.sources)
  fi
  if [[ -z "$entry" ]]; then
    entry=$'Types: deb-src\nURIs: http://deb.debian.org/debian\nSuites: bookworm bookworm-updates\nComponents: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n'
  fi
  echo "meshlab-source: adding a deb-src entry for bookworm in $src_file" >&2
  printf '%s\n' "$entry" | $SUDO tee "$src_file" > /dev/null || die "cannot write $src_file (run as root)"
  $SUDO apt-get update -q >&2 || die "apt-get update failed"
elif ! apt-get source --print-uris meshlab > /dev/null 2>&1; then
  $SUDO apt-get update -q >&2 || die "apt-get update failed"
fi

command -v dpkg-source > /dev/null 2>&1 || die "dpkg-source missing: install dpkg-dev (packaging/install-deps.sh)"
tmp="$DEST/.tmp.$$"
rm -rf "$tmp"
mkdir -p "$tmp"
echo "meshlab-source: apt-get source meshlab (log in $DEST/apt-source.log)" >&2
if ! (cd "$tmp" && apt-get source -q meshlab > "$DEST/apt-source.log" 2>&1); then
  tail -n 5 "$DEST/apt-source.log" >&2 || true
  rm -rf "$tmp"
  die "apt-get source meshlab failed (full log: $DEST/apt-source.log)"
fi
for d in "$tmp"/meshlab-*/; do
  [[ -d "$d" ]] && mv "${d%/}" "$DEST/"
done
rm -rf "$tmp"
tree=$(find_tree) || die "the unpacked source has no src/common/interfaces.h + vcglib/ in $DEST"
echo "meshlab-source: unpacked $tree" >&2
echo "$tree"
