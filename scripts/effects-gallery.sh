#!/usr/bin/env bash
# The pictures of docs/effects.md: every image-space effect on the sample scan (the lion) and on
# the generated house scene (`pointnpr bench quality --scene-ply`, segments = surface kinds), the
# three layerings of the paper's figure 12 on the house scene, and the urban example (per-class
# recolouring and filters) on the CGAL aerial scan. Every picture is one `pointnpr render
# --effects` call; the pipeline files are written here, next to the pictures' sources.
#
#   scripts/effects-gallery.sh BUILD_DIR [OUT_DIR]      (OUT_DIR defaults to docs/images/effects)
#
# Needs the scans of scripts/fetch-scans.sh (cached in .cache/scans, PNPR_SCANS_CACHE) and
# ImageMagick (convert, montage: Debian package imagemagick) for the small palette PNGs.
set -euo pipefail
die() { echo "effects-gallery: $*" >&2; exit 1; }
[[ $# -ge 1 && $# -le 2 ]] || { echo "usage: scripts/effects-gallery.sh BUILD_DIR [OUT_DIR]" >&2; exit 2; }
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=$(cd "$1" 2> /dev/null && pwd) || die "no build directory $1"
BIN="$BUILD/pointnpr"
[[ -x "$BIN" ]] || die "$BIN is missing: build first"
command -v convert > /dev/null && command -v montage > /dev/null || die "ImageMagick (convert, montage) is needed"
cd "$ROOT"
OUT=${2:-docs/images/effects}
CACHE=${PNPR_SCANS_CACHE:-.cache/scans}
WORK="$BUILD/effects-gallery"
mkdir -p "$OUT" "$WORK"
declare -A SCAN
while read -r name path; do SCAN[$name]=$path; done < <(bash scripts/fetch-scans.sh "$CACHE")
SIZE=480x360
# montage's default font (Helvetica) is often absent: DejaVu Sans, else any font it knows
f=$(convert -list font 2> /dev/null | sed -n 's/^ *Font: //p' | grep -m 1 -x 'DejaVu-Sans' ||
    convert -list font 2> /dev/null | sed -n 's/^ *Font: //p' | head -n 1 || true)
FONT=()
[[ -n "$f" ]] && FONT=(-font "$f")

# small PNG: 8-bit palette of at most 128 colours
shrink() { convert "$1" -colors 128 PNG8:"$2"; }
render() { # IN OUT PIPELINE [options]
  local in=$1 out=$2 fx=$3; shift 3
  "$BIN" render "$in" -o "$WORK/$out.png" --size "$SIZE" --effects "$fx" --quiet "$@"
  shrink "$WORK/$out.png" "$OUT/$out.png"
}

# ---- the scans ----
"$BIN" convert "${SCAN[lion]}" -o "$WORK/lion.ply" --quiet
"$BIN" bench quality --scene-ply "$WORK/house.ply"
"$BIN" convert "${SCAN[b9_training]}" -o "$WORK/b9.ply" --ascii --quiet
# the aerial scan's colours are its class colours: dropped, so that it is shaded in greys
awk 'f { print $1, $2, $3, $7 } /end_header/ { f = 1 }' "$WORK/b9.ply" > "$WORK/b9.xyz"
"$BIN" convert "$WORK/b9.xyz" --columns x,y,z,label -o "$WORK/b9_grey.ply" --quiet

# ---- every effect with its defaults, on the lion and on the house ----
printf '# nothing: the raster\n' > "$WORK/none.fx"
effects=(none smooth toon watercolour oil pencil posterise grade edges)
for e in "${effects[@]}"; do
  [[ $e == none ]] || printf '%s\n' "$e" > "$WORK/$e.fx"
done
printf 'grade saturation=0.2 tint_r=0.55 tint_g=0.45 tint_b=0.35 recolour=0.8\n' > "$WORK/grade.fx"
for scan in lion house; do
  cells=()
  for e in "${effects[@]}"; do
    render "$WORK/$scan.ply" "$scan-$e" "$WORK/$e.fx"
    cells+=(-label "$e" "$OUT/$scan-$e.png")
  done
  montage "${FONT[@]}" "${cells[@]}" -tile 3x -geometry 320x240+4+4 "$WORK/$scan-sheet.png"
  shrink "$WORK/$scan-sheet.png" "$OUT/$scan-sheet.png"
done

# ---- the presets on the lion ----
cells=()
while read -r p; do
  printf 'preset %s\n' "$p" > "$WORK/preset-$p.fx"
  render "$WORK/lion.ply" "lion-preset-$p" "$WORK/preset-$p.fx"
  cells+=(-label "preset $p" "$OUT/lion-preset-$p.png")
done < <(printf '%s\n' cartoon watercolour oil pencil poster muted ink)
montage "${FONT[@]}" "${cells[@]}" -tile 4x -geometry 320x240+4+4 "$WORK/lion-presets.png"
shrink "$WORK/lion-presets.png" "$OUT/lion-presets.png"

# ---- the presets on scans they were not tuned on: a colourless building, an RGB-D frame ----
"$BIN" convert "${SCAN[building]}" -o "$WORK/building.ply" --quiet
"$BIN" convert "${SCAN[mug_stereo]}" -o "$WORK/mug.ply" --quiet
for scan in building mug; do
  cam=()
  [[ $scan == mug ]] && cam=(--eye 0,0,0 --target 0,0,1 --up -y --fov 30) # from the sensor
  render "$WORK/$scan.ply" "$scan-raw" "$WORK/none.fx" "${cam[@]}"
  cells=(-label raw "$OUT/$scan-raw.png")
  for p in cartoon watercolour oil pencil poster muted ink; do
    render "$WORK/$scan.ply" "$scan-preset-$p" "$WORK/preset-$p.fx" "${cam[@]}"
    cells+=(-label "preset $p" "$OUT/$scan-preset-$p.png")
  done
  montage "${FONT[@]}" "${cells[@]}" -tile 4x -geometry 320x240+4+4 "$WORK/$scan-presets.png"
  shrink "$WORK/$scan-presets.png" "$OUT/$scan-presets.png"
  rm -f "$OUT/$scan-raw.png" "$OUT"/"$scan"-preset-*.png # only the sheet is shown
done

# ---- figure 12: the three layerings on the house scene (segments per surface kind) ----
cat > "$WORK/house.fx" <<'FX'
# the generated house scene: 1 ground, 2 wall, 3 roof, 4 trunk, 5 crown, 6 sphere
toon
node ground labels 1
clear
grade saturation=0.6 brightness=0.1
watercolour
node trees labels 4 5
clear
watercolour
node roof labels 3
oil
FX
cp "$WORK/house.fx" "$OUT/house.fx"
cells=()
for m in none fragment inpainted; do
  render "$WORK/house.ply" "house-layering-$m" "$WORK/house.fx" --layering "$m" --size 640x480
  cells+=(-label "layering $m" "$OUT/house-layering-$m.png")
done
montage "${FONT[@]}" "${cells[@]}" -tile 3x -geometry 420x315+4+4 "$WORK/house-layering.png"
shrink "$WORK/house-layering.png" "$OUT/house-layering.png"
# the same three, cropped at full size around the gabled house's roof
for m in none fragment inpainted; do
  convert "$WORK/house-layering-$m.png" -crop 200x150+330+60 +repage -scale 200% "$WORK/crop-$m.png"
done
montage "${FONT[@]}" -label none "$WORK/crop-none.png" -label fragment "$WORK/crop-fragment.png" \
  -label inpainted "$WORK/crop-inpainted.png" -tile 3x -geometry +4+4 "$WORK/house-layering-crop.png"
shrink "$WORK/house-layering-crop.png" "$OUT/house-layering-crop.png"

# ---- the urban example: the aerial scan, per class ----
cat > "$WORK/aerial.fx" <<'FX'
# the CGAL aerial training scan without its class colours (shaded greys); classes ground 0,
# vegetation 1, roof 2; the unclassified rest (label 4294967295) stays with the root: toon greys
toon levels=6
node ground labels 0
clear
grade tint_r=0.95 tint_g=0.85 tint_b=0.6 recolour=1
watercolour
node vegetation labels 1
clear
grade tint_r=0.45 tint_g=0.8 tint_b=0.35 recolour=1 contrast=1.3
watercolour
node roofs labels 2
clear
grade tint_r=0.9 tint_g=0.45 tint_b=0.35 recolour=1
oil
FX
cp "$WORK/aerial.fx" "$OUT/aerial.fx"
render "$WORK/b9_grey.ply" aerial-raw "$WORK/none.fx" --size 640x480
render "$WORK/b9_grey.ply" aerial-effects "$WORK/aerial.fx" --size 640x480
render "$WORK/house.ply" house-effects "$WORK/house.fx" --size 640x480
echo "effects-gallery: pictures in $OUT" >&2
