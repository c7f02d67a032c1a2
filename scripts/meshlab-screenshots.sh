#!/usr/bin/env bash
# Screenshots of the pointnpr filter dialogs in the real MeshLab 2020.09 GUI (docs/meshlab.md).
#
#   scripts/meshlab-screenshots.sh BUILD_DIR [OUT_DIR]      (OUT_DIR: docs/images)
#
# Starts /usr/bin/meshlab under its own Xvfb display (1280x1024, no window manager) from a private
# host folder (a hard link of the binary + plugins/ with the system plugins and BUILD_DIR's
# libfilter_pointnpr.so / libdecorate_pointnpr.so; LD_LIBRARY_PATH=/usr/lib/x86_64-linux-gnu/meshlab,
# a fresh HOME), opens BUILD_DIR/demo/lion.ply (else a generated cube), opens each "NPR: ..." entry
# of Filters -> Point Set with xdotool clicks, saves the dialog window (ImageMagick `import -window`)
# as OUT_DIR/meshlab-dialog-<name>.png and closes it; then turns Render -> NPR render on and saves
# the main window as OUT_DIR/meshlab-dialog-decorate.png, and with the decorator's panel unfolded as
# OUT_DIR/meshlab-decorate-panel.png.
#
# Needs: meshlab, xvfb, xdotool, imagemagick, x11-utils. The menu positions are those of Debian's
# meshlab 2020.09+dfsg1 with its own plugins plus ours, main window at 0,0 sized 1280x1000; every
# dialog's window title is checked, so a different menu layout fails instead of taking wrong pictures.
set -uo pipefail

BUILD=${1:?usage: meshlab-screenshots.sh BUILD_DIR [OUT_DIR]}
[[ -d "$BUILD" ]] || { echo "meshlab-screenshots: no build folder $BUILD" >&2; exit 1; }
BUILD=$(cd "$BUILD" && pwd)
SRC=$(cd "$(dirname "$0")/.." && pwd)
OUT=${2:-$SRC/docs/images}
MLLIB=${PNPR_MESHLAB_LIBDIR:-/usr/lib/x86_64-linux-gnu/meshlab}
GUI_BIN=${PNPR_MESHLAB_GUI:-/usr/bin/meshlab}
FILTER_SO="$BUILD/plugin/meshlab/libfilter_pointnpr.so"
DECORATE_SO="$BUILD/plugin/meshlab/libdecorate_pointnpr.so"

die() { echo "meshlab-screenshots: $*" >&2; exit 1; }
for t in Xvfb xdotool import xwininfo; do command -v "$t" > /dev/null || die "$t not found (apt-get install xvfb xdotool imagemagick x11-utils)"; done
[[ -x "$GUI_BIN" ]] || die "$GUI_BIN not found"
[[ -f "$FILTER_SO" ]] || die "$FILTER_SO not built"
mkdir -p "$OUT" || die "cannot create $OUT"
OUT=$(cd "$OUT" && pwd)

T=$(mktemp -d /tmp/pnpr-screenshots.XXXXXX)
XVFB_PID="" ML_PID=""
cleanup() {
  [[ -n "$ML_PID" ]] && { kill "$ML_PID" 2> /dev/null; wait "$ML_PID" 2> /dev/null; }
  [[ -n "$XVFB_PID" ]] && { kill "$XVFB_PID" 2> /dev/null; wait "$XVFB_PID" 2> /dev/null; }
  rm -rf "$T"
}
trap cleanup EXIT

# ---- private host folder ----
mkdir -p "$T/host/plugins" "$T/home"
chmod 700 "$T/home"
ln "$GUI_BIN" "$T/host/meshlab" 2> /dev/null || cp "$GUI_BIN" "$T/host/meshlab" || die "cannot copy $GUI_BIN"
for p in "$MLLIB"/plugins/*.so; do
  [[ "$(basename "$p")" == lib*_pointnpr.so ]] && continue
  ln -s "$p" "$T/host/plugins/"
done
ln -s "$(cd "$(dirname "$FILTER_SO")" && pwd)/libfilter_pointnpr.so" "$T/host/plugins/"
[[ -f "$DECORATE_SO" ]] && ln -s "$(cd "$(dirname "$DECORATE_SO")" && pwd)/libdecorate_pointnpr.so" "$T/host/plugins/"

# ---- input cloud ----
CLOUD="$BUILD/demo/lion.ply"
if [[ ! -f "$CLOUD" ]]; then
  CLOUD="$T/cube.ply"
  awk -v n=50 'BEGIN { c = (n + 1) ^ 3 - (n - 1) ^ 3
    printf "ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\nend_header\n", c
    for (i = 0; i <= n; i++) for (j = 0; j <= n; j++) for (k = 0; k <= n; k++) {
      if (i > 0 && i < n && j > 0 && j < n && k > 0 && k < n) continue
      printf "%g %g %g\n", i / n, j / n, k / n } }' > "$CLOUD"
fi

# ---- Xvfb on a free display ----
for d in $(seq $((100 + RANDOM % 300)) 500); do
  [[ -e /tmp/.X$d-lock || -e /tmp/.X11-unix/X$d ]] && continue
  Xvfb ":$d" -nolisten tcp -screen 0 1280x1024x24 > "$T/xvfb.log" 2>&1 &
  XVFB_PID=$!
  for _ in $(seq 1 50); do
    [[ -e /tmp/.X11-unix/X$d ]] && break
    sleep 0.1
  done
  if [[ -e /tmp/.X11-unix/X$d ]]; then export DISPLAY=":$d"; break; fi
  kill "$XVFB_PID" 2> /dev/null; wait "$XVFB_PID" 2> /dev/null; XVFB_PID=""
done
[[ -n "$XVFB_PID" ]] || die "could not start Xvfb"

# ---- MeshLab ----
(cd "$T" && HOME="$T/home" XDG_RUNTIME_DIR="$T/home" \
  LD_LIBRARY_PATH="$MLLIB${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" exec "$T/host/meshlab" "$CLOUD") > "$T/meshlab.log" 2>&1 &
ML_PID=$!

# wait_window TITLE_REGEX SECONDS: prints the id of the visible window with that title
wait_window() {
  local i w
  for i in $(seq 1 $((10 * $2))); do
    w=$(xdotool search --onlyvisible --name "$1" 2> /dev/null | head -n 1)
    [[ -n "$w" ]] && { echo "$w"; return 0; }
    kill -0 "$ML_PID" 2> /dev/null || return 1
    sleep 0.1
  done
  return 1
}
MAIN=$(wait_window '^MeshLab 2020' 60) || { tail -n 20 "$T/meshlab.log"; die "MeshLab's main window did not appear"; }
for _ in $(seq 1 600); do grep -q "All files opened" "$T/meshlab.log" && break; sleep 0.1; done
grep -q "Opened mesh" "$T/meshlab.log" || { tail -n 20 "$T/meshlab.log"; die "MeshLab did not open $CLOUD"; }
xdotool windowmove "$MAIN" 0 0 windowsize "$MAIN" 1280 1000
sleep 2
click() { xdotool mousemove "$1" "$2" click 1; sleep "${3:-0.7}"; }

# Filters -> Point Set -> entry ENTRY_Y; the NPR entries in the submenu (alphabetical), their y
FILTERS_X=120 FILTERS_Y=10 POINTSET_X=155 POINTSET_Y=386 ENTRY_X=627
NAMES=(features lines jseg components select)
TITLES=("NPR: Compute feature degree and classify points" "NPR: Profile lines" "NPR: Segment .JSEG"
  "NPR: Segment .connected components" "NPR: Select feature points")
YS=(611 636 661 686 711)
made=()
for i in "${!NAMES[@]}"; do
  click $FILTERS_X $FILTERS_Y
  click $POINTSET_X $POINTSET_Y
  click $ENTRY_X "${YS[$i]}" 1.5
  if ! w=$(wait_window "^${TITLES[$i]}" 10); then
    echo "meshlab-screenshots: the dialog '${TITLES[$i]}' did not appear (menu layout differs?)" >&2
    [[ -n "${PNPR_SHOTS_DEBUG:-}" ]] && import -window root "$PNPR_SHOTS_DEBUG-${NAMES[$i]}.png"
    xdotool key Escape Escape Escape
    continue
  fi
  sleep 1
  import -window "$w" "$OUT/meshlab-dialog-${NAMES[$i]}.png" && made+=("meshlab-dialog-${NAMES[$i]}.png")
  # the dialog's Close button: bottom-left quarter, 23 px above its bottom edge
  eval "$(xdotool getwindowgeometry --shell "$w")"
  click $((X + WIDTH / 4)) $((Y + HEIGHT - 23))
  xdotool search --onlyvisible --name "^${TITLES[$i]}" > /dev/null 2>&1 && echo "meshlab-screenshots: '${TITLES[$i]}' still open" >&2
done

# Render -> NPR render (the decorator; default style), then the main window
if [[ -f "$DECORATE_SO" ]]; then
  click 178 10
  click 215 336 1
  for _ in $(seq 1 1200); do
    grep -qE "pointnpr decorator: uploaded" "$T/meshlab.log" && break
    kill -0 "$ML_PID" 2> /dev/null || break
    sleep 0.1
  done
  sleep 3
  if grep -q "Enabled Decorate mode NPR render" "$T/meshlab.log"; then
    import -window "$MAIN" "$OUT/meshlab-dialog-decorate.png" && made+=("meshlab-dialog-decorate.png")
    # the decorator's panel: unfold "NPR render" in the layer dialog's decorator list (its arrow at
    # 883,666 in this window layout), then the main window again
    click 883 666 1.5
    import -window "$MAIN" "$OUT/meshlab-decorate-panel.png" && made+=("meshlab-decorate-panel.png")
  else
    echo "meshlab-screenshots: the NPR render decorator did not turn on" >&2
  fi
fi

grep -E "pointnpr|NPR" "$T/meshlab.log" | head -n 20
echo "meshlab-screenshots: wrote ${#made[@]} screenshots to $OUT: ${made[*]}"
((${#made[@]} >= 5))
