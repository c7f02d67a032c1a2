#!/usr/bin/env bash
# Segment-specific image-space effects (`pointnpr render --effects`, docs/effects.md) on a 1M-point
# labelled cloud at 1920x1080: the effects frame against the plain points frame, against the
# number of segments S, the inpainting radius R and the layering. Writes OUT_DIR/effects.md (the
# tables of docs/benchmarks.md) and prints it. Runs serially; every figure is the median of REPS
# runs of the whole `pointnpr render` process.
set -euo pipefail

usage() {
  cat <<'EOF'
usage: bash bench/effects.sh BUILD_DIR [OUT_DIR]
  BUILD_DIR  a configured and built tree: BUILD_DIR/pointnpr and BUILD_DIR/bench/effects_scene
             (make pointnpr_cli effects_scene; a Release build for figures worth quoting)
  OUT_DIR    where clouds, pipeline files, logs, images and effects.md go
             (default BUILD_DIR/bench-effects)
Environment (optional): REPS (repetitions per case, median taken; default 3),
  POINTS (default 1000000), SIZE (default 1920x1080).
Measures (a) plain `render --style points` and a 1-layer points frame through the effects path
(no effect, no inpainting, layering none) as the baseline, (b) S in {1 2 4 8 16 32 64} segments,
per_label on, with posterise (cheap) and toon (expensive), default inpainting, (c) inpainting
radius R in {1 3 8 16 32} at S = 8, (d) the three layerings at S = 8 ((c), (d): posterise,
so that the filter does not hide the inpainting and compositing).
EOF
  exit "${1:-2}"
}

[ $# -ge 1 ] && [ $# -le 2 ] || usage 2
case $1 in -h | --help) usage 0 ;; esac
build=$1
out=${2:-$build/bench-effects}
cli=$build/pointnpr
gen=$build/bench/effects_scene
reps=${REPS:-3}
points=${POINTS:-1000000}
size=${SIZE:-1920x1080}
for exe in "$cli" "$gen"; do
  [ -x "$exe" ] || { echo "bench/effects.sh: $exe is missing: make -C $build pointnpr_cli effects_scene" >&2; exit 1; }
done
[ -x /usr/bin/time ] || { echo "bench/effects.sh: needs /usr/bin/time (GNU time)" >&2; exit 1; }
[[ $reps =~ ^[1-9][0-9]*$ ]] || { echo "bench/effects.sh: REPS must be a positive integer, got '$reps'" >&2; exit 2; }
mkdir -p "$out/clouds" "$out/pipes" "$out/logs" "$out/png"

segments_list=(1 2 4 8 16 32 64)
radii=(1 3 8 16 32)

echo "== generating the test clouds: $points points, S segments (bench/effects_scene)" >&2
for s in "${segments_list[@]}"; do
  c=$out/clouds/scene_${points}_s$s.ply
  [ -s "$c" ] || "$gen" "$c" --points "$points" --segments "$s"
done

# Pipeline files (format: the comment at the top of effects/pipeline.c).
printf 'style points\ninpaint off\nlayering none\n' > "$out/pipes/plain.txt"
printf 'per_label on\nposterise\n' > "$out/pipes/posterise.txt"
printf 'per_label on\ntoon\n' > "$out/pipes/toon.txt"
for r in "${radii[@]}"; do printf 'per_label on\nposterise\ninpaint radius=%s\n' "$r" > "$out/pipes/posterise_r$r.txt"; done

median() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
div() { awk -v a="$1" -v b="$2" -v f="${3:-%.2f}" 'BEGIN { if (b > 0) printf f, a / b; else print "-" }'; }

# run_case ID CLOUD PIPE [RENDER ARGS...]: REPS runs of `pointnpr render`; PIPE "" = plain points.
# Sets M_LAYERS M_RASTER M_FILTER M_INPAINT M_COMP M_FRAME (the sum of the four steps) M_WALL
# (whole process, s) M_RSS (peak, MB): medians over the repetitions (each column separately).
run_case() {
  local id=$1 cloud=$2 pipe=$3
  shift 3
  local -a args=("$cloud" -o "$out/png/$id.png" --size "$size" "$@")
  [ -n "$pipe" ] && args+=(--effects "$pipe")
  local -a lay=() ras=() fil=() inp=() com=() fra=() wal=() rss=()
  local r log tf line w m l a b c d
  for r in $(seq 1 "$reps"); do
    log=$out/logs/$id.$r.log
    tf=$out/logs/$id.$r.time
    echo "== $id, run $r/$reps" >&2
    /usr/bin/time -f '%e %M' -o "$tf" "$cli" render "${args[@]}" 2> "$log" ||
      { echo "bench/effects.sh: pointnpr render failed ($id), see $log:" >&2; tail -5 "$log" >&2; exit 1; }
    read -r w m < "$tf"
    wal+=("$w"); rss+=("$(awk -v k="$m" 'BEGIN { printf "%.0f", k / 1024 }')")
    if [ -n "$pipe" ]; then
      line=$(grep -m1 ': effects: [0-9]* layers' "$log" |
        sed -E 's/.*effects: ([0-9]+) layers \(raster ([0-9.]+) s, filters ([0-9.]+) s, inpainting ([0-9.]+) s, compositing ([0-9.]+) s\).*/\1 \2 \3 \4 \5/')
      read -r l a b c d <<< "$line"
      lay+=("$l"); ras+=("$a"); fil+=("$b"); inp+=("$c"); com+=("$d")
      fra+=("$(awk -v a="$a" -v b="$b" -v c="$c" -v d="$d" 'BEGIN { printf "%.2f", a + b + c + d }')")
    else
      lay+=(0); ras+=(0); fil+=(0); inp+=(0); com+=(0); fra+=(0)
    fi
  done
  M_LAYERS=$(median "${lay[@]}"); M_RASTER=$(median "${ras[@]}"); M_FILTER=$(median "${fil[@]}")
  M_INPAINT=$(median "${inp[@]}"); M_COMP=$(median "${com[@]}"); M_FRAME=$(median "${fra[@]}")
  M_WALL=$(median "${wal[@]}"); M_RSS=$(median "${rss[@]}")
  echo "   $id: layers $M_LAYERS, raster $M_RASTER, filters $M_FILTER, inpainting $M_INPAINT, compositing $M_COMP, frame $M_FRAME s, process $M_WALL s (${wal[*]}), $M_RSS MB" >&2
}

t0=$(date +%s)
res=$out/effects.md

# (a) the baseline: the plain points render, and one points layer through the effects path.
s8=$out/clouds/scene_${points}_s8.ply
run_case plain_points "$s8" "" --style points
base_wall=$M_WALL base_rss=$M_RSS
run_case fx_plain "$s8" "$out/pipes/plain.txt"
base_frame=$M_FRAME fxp_wall=$M_WALL fxp_raster=$M_RASTER fxp_comp=$M_COMP fxp_rss=$M_RSS

row() { # LABEL: one table row from the M_ values
  echo "| $1 | $M_LAYERS | $M_RASTER | $M_FILTER | $M_INPAINT | $M_COMP | $M_FRAME | $(div "$M_FRAME" "$base_frame") | $(div "$M_FRAME" "$M_LAYERS" %.3f) | $M_WALL | $(div "$M_WALL" "$base_wall") | $M_RSS |"
}
header='| case | layers | raster s | filters s | inpainting s | compositing s | frame s | x points frame | frame s per layer | process s | x points process | peak MB |'
rule='|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|'

{
  echo "Machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); $(date -u +%Y-%m-%d)"
  echo "Cloud: $points points (bench/effects_scene), image $size, median of $reps runs of the whole process."
  echo
  echo "(a) Baseline"
  echo
  echo "| case | frame s | process s | peak MB |"
  echo "|---|---:|---:|---:|"
  echo "| \`render --style points\` (plain, no --effects) | - | $base_wall | $base_rss |"
  echo "| 1 points layer through --effects (no effect, inpaint off, layering none): raster $fxp_raster + compositing $fxp_comp | $base_frame | $fxp_wall | $fxp_rss |"
  echo
} > "$res"

# (b) segments S, posterise and toon, default inpainting (radius 3), layering inpainted.
{ echo "(b) Segments S (per_label on, one layer per segment; default inpainting, layering inpainted)"; echo; echo "$header"; echo "$rule"; } >> "$res"
for fx in posterise toon; do
  for s in "${segments_list[@]}"; do
    run_case "${fx}_s$s" "$out/clouds/scene_${points}_s$s.ply" "$out/pipes/$fx.txt"
    row "$fx, S = $s" >> "$res"
  done
done
echo >> "$res"

# (c) inpainting radius at S = 8, posterise (a cheap filter, so that inpainting shows).
{ echo "(c) Inpainting radius R (S = 8, posterise, layering inpainted)"; echo; echo "$header"; echo "$rule"; } >> "$res"
for r in "${radii[@]}"; do
  run_case "posterise_s8_r$r" "$s8" "$out/pipes/posterise_r$r.txt"
  row "posterise, R = $r" >> "$res"
done
echo >> "$res"

# (d) layerings at S = 8, posterise, default radius.
{ echo "(d) Layering (S = 8, posterise, R = 3)"; echo; echo "$header"; echo "$rule"; } >> "$res"
for lm in inpainted fragment none; do
  run_case "posterise_s8_$lm" "$s8" "$out/pipes/posterise.txt" --layering "$lm"
  row "posterise, layering $lm" >> "$res"
done
echo >> "$res"
echo "Whole run: $(( $(date +%s) - t0 )) s (bash bench/effects.sh $build $out, REPS=$reps)." >> "$res"
cat "$res"
