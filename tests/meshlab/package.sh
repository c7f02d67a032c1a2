#!/usr/bin/env bash
# The Debian package (packaging/cpack.cmake): builds the .deb with CPack, checks its control file
# and contents with dpkg-deb, extracts it (dpkg-deb -x into a folder; nothing is installed into
# the system) and runs the EXTRACTED files: `pointnpr --version`, and meshlabserver from a
# private host folder whose plugins/ holds the system plugins plus the extracted plugins
# (tests/meshlab/run.sh load: filter list, parameters, the features filter on a cube), then
# checks the cube's vertex quality (feature degree) is in [0,1] and not all 0.
#
#   tests/meshlab/package.sh CPACK CPACK_CONFIG WORKDIR MESHLAB_VERSION PLUGIN_DIR [DECORATE_SO_NAME]
#     MESHLAB_VERSION: the meshlab version read at configure time (the .deb must depend on it, =)
#     PLUGIN_DIR: MeshLab's plugin folder (/usr/lib/x86_64-linux-gnu/meshlab/plugins): where the
#                 plugins must be in the package; its parent is MeshLab's library folder
#     DECORATE_SO_NAME: libdecorate_pointnpr.so when the decorator is built (must be in the .deb)
set -uo pipefail

CPACK=${1:?usage: package.sh CPACK CPACK_CONFIG WORKDIR MESHLAB_VERSION PLUGIN_DIR [DECORATE_SO_NAME]}
CONFIG=${2:?}
W=${3:?}
MLVER=${4:?}
PLUGDIR=${5:?}
DECORATE=${6:-}
HERE=$(cd "$(dirname "$0")" && pwd)
FAILS=0
log() { echo "[package] $*"; }
fail() { echo "[package] FAIL: $*"; FAILS=$((FAILS + 1)); }
die() { echo "[package] FAIL: $*"; exit 1; }

[[ -f "$CONFIG" ]] || die "$CONFIG not found (configure first)"
rm -rf "$W"
mkdir -p "$W/out" || die "cannot create $W"

# ---- build the .deb (into WORKDIR/out, not the build folder's top) ----
start=$(date +%s)
"$CPACK" --config "$CONFIG" -G DEB -B "$W/out" > "$W/cpack.log" 2>&1 || { cat "$W/cpack.log"; die "cpack failed"; }
shopt -s nullglob
debs=("$W"/out/*.deb)
((${#debs[@]} == 1)) || { cat "$W/cpack.log"; die "expected one .deb in $W/out, found ${#debs[@]}"; }
DEB=${debs[0]}
log "built $(basename "$DEB") in $(($(date +%s) - start)) s"

# ---- control file ----
dpkg-deb -I "$DEB" > "$W/info.txt" || die "dpkg-deb -I failed"
cat "$W/info.txt"
depends=$(dpkg-deb -f "$DEB" Depends)
# one entry per line, "name (op version)" or alternatives "a | b"
tr ',' '\n' <<< "$depends" | sed 's/^ *//; s/ *$//' > "$W/depends.txt"
grep -qxF "meshlab (= $MLVER)" "$W/depends.txt" || fail "Depends has no 'meshlab (= $MLVER)': $depends"
[[ $(awk '$1 == "meshlab"' "$W/depends.txt" | wc -l) == 1 ]] || fail "Depends names meshlab more than once: $depends"
installed=$(dpkg-query -W -f='${Version}' meshlab 2> /dev/null)
[[ "$installed" == "$MLVER" ]] ||
  fail "the installed meshlab is '$installed' but the build was configured against '$MLVER' (reconfigure)"
# the libraries the binaries link (dpkg-shlibdeps) and the ones the renderer loads at run time
dep() { awk -v p="$1" '$1 == p { ok = 1 } END { exit !ok }' "$W/depends.txt"; }
for p in libc6 libstdc++6 libopenmesh1 libqt5core5a; do
  dep "$p" || fail "Depends lacks $p: $depends"
done
# libpng comes with the renderer (PNG output), which the decorator needs: a build without libepoxy
# or libpng has neither
if [[ -n "$DECORATE" ]]; then
  for p in libpng16-16 libepoxy0 libegl1 libgl1 libgl1-mesa-dri; do
    dep "$p" || fail "Depends lacks $p: $depends"
  done
fi
[[ $(dpkg-deb -f "$DEB" Package) == pointnpr ]] || fail "package name is not pointnpr"
[[ $(dpkg-deb -f "$DEB" Architecture) == $(dpkg --print-architecture) ]] || fail "architecture is not $(dpkg --print-architecture)"

# ---- contents ----
dpkg-deb -c "$DEB" > "$W/contents.txt" || die "dpkg-deb -c failed"
cat "$W/contents.txt"
has() { awk -v f="./${1#/}" -v m="$2" '$NF == f && $1 ~ m { ok = 1 } END { exit !ok }' "$W/contents.txt"; }
has /usr/bin/pointnpr '^-rwxr-xr-x' || fail "no executable ./usr/bin/pointnpr in the package"
has "$PLUGDIR/libfilter_pointnpr.so" '^-' || fail "no .$PLUGDIR/libfilter_pointnpr.so in the package"
if [[ -n "$DECORATE" ]]; then
  has "$PLUGDIR/$DECORATE" '^-' || fail "no .$PLUGDIR/$DECORATE in the package"
fi
# a runtime package: no static libraries, no headers, nothing outside /usr
grep -qE '\.a$|/include/' "$W/contents.txt" && fail "static libraries or headers in the package"
awk '$NF !~ /^\.\/(usr\/)?$/ && $NF !~ /^\.\/usr\// { bad++ } END { exit bad ? 1 : 0 }' "$W/contents.txt" ||
  fail "files outside /usr in the package"

# ---- extract (never installed) and run the extracted files ----
ROOT="$W/root"
dpkg-deb -x "$DEB" "$ROOT" || die "dpkg-deb -x failed"
CLI="$ROOT/usr/bin/pointnpr"
ver=$("$CLI" --version 2>&1) || fail "extracted pointnpr --version failed: $ver"
want=$(dpkg-deb -f "$DEB" Version)
want=${want%-*} # upstream version (without the Debian release)
log "extracted pointnpr --version: $ver"
[[ "$ver" == "pointnpr $want" ]] || fail "pointnpr --version says '$ver', expected 'pointnpr $want'"

FILTER="$ROOT$PLUGDIR/libfilter_pointnpr.so"
DECO=""
[[ -n "$DECORATE" ]] && DECO="$ROOT$PLUGDIR/$DECORATE"
[[ -f "$FILTER" ]] || die "extracted filter plugin missing: $FILTER"
MLLIB=$(dirname "$PLUGDIR")
# both plugins resolve every symbol against the system libraries (MeshLab's folder on the path
# as MeshLab's own binaries have it) and export the Qt plugin entry points
for so in "$FILTER" $DECO; do
  LD_LIBRARY_PATH="$MLLIB" ldd -r "$so" > "$W/ldd-$(basename "$so").txt" 2>&1
  if grep -qE "not found|undefined symbol" "$W/ldd-$(basename "$so").txt"; then
    fail "$(basename "$so"): unresolved libraries/symbols:"; grep -E "not found|undefined symbol" "$W/ldd-$(basename "$so").txt" | head -5
  fi
  nm -D --defined-only "$so" | grep -q ' qt_plugin_instance$' || fail "$(basename "$so") does not export qt_plugin_instance"
done

# meshlabserver with the extracted plugins (run.sh links them into its private host's plugins/)
PNPR_MESHLAB_LIBDIR="$MLLIB" bash "$HERE/run.sh" load "$FILTER" "$CLI" "$W/meshlab" $DECO ||
  fail "meshlabserver with the extracted plugins (tests/meshlab/run.sh load) failed"
T="$W/meshlab/load"
for so in libfilter_pointnpr.so $DECORATE; do
  target=$(readlink -f "$T/host/plugins/$so")
  [[ "$target" == "$(readlink -f "$ROOT$PLUGDIR/$so")" ]] || fail "host plugins/$so is '$target', not the extracted file"
done
# no loader message about any plugin in the host folder (a bad decorator would name its file)
grep -hiE "cannot load|undefined symbol|not a valid" "$T"/*.log && fail "plugin loader errors in meshlabserver's output"
# the features filter's output: 602 cube points, vertex quality = feature degree in [0,1], some > 0
if [[ -f "$T/out.ply" ]] && "$CLI" convert "$T/out.ply" -o "$W/out-ascii.ply" --ascii --quiet; then
  awk '/^element vertex/ { nv = $3 } /^property/ && !b { col[$NF] = np++ } /^end_header/ { b = 1; next }
    b && nv > 0 { nv--; n++; q = $(col["quality"] + 1); if (q < 0 || q > 1 || q != q + 0) bad++; if (q > 0) pos++; if (q > mx) mx = q }
    END { printf "[package] features on the cube: %d points, %d with quality > 0, max %.3f, %d outside [0,1]\n", n, pos, mx, bad
          exit ("quality" in col && n == 602 && !bad && pos > 0) ? 0 : 1 }' "$W/out-ascii.ply" ||
    fail "feature degrees (vertex quality) of the cube are missing or outside [0,1]"
else
  fail "no features output from meshlabserver ($T/out.ply), or the extracted pointnpr cannot read it"
fi

if ((FAILS > 0)); then
  echo "[package] $FAILS check(s) failed (work folder $W)"
  exit 1
fi
log "OK"
