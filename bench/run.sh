#!/usr/bin/env bash
# make bench: the feature pipeline on 1M generated points vs PCL's NormalEstimationOMP and Open3D's
# normal estimation on the same cloud, in the same run, all on the same number of threads
# (PNPR_BENCH_THREADS, default 2). Writes build/bench/features.md (the table for docs/benchmarks.md).
#   bash bench/run.sh BUILD_DIR [POINTS] [K]
set -euo pipefail
build=${1:-build}
points=${2:-1000000}
k=${3:-16}
out=$build/bench
mkdir -p "$out"
cloud=$out/scene_${points}.ply
threads=${PNPR_BENCH_THREADS:-2}
pcl=$build/bench/normals_pcl

# Ours, PCL and Open3D take turns, 3 rounds each, and the medians are compared: on a shared
# 2-core machine a background process slows OpenMP (the peers) far more than our threads, so a
# single run of each can be misleading either way.
rounds=3
: > "$out/ours_all.txt"; : > "$out/open3d_all.txt"; : > "$out/pcl_all.txt"
for r in $(seq 1 $rounds); do
  echo "== round $r/$rounds: pointnpr features pipeline, $points points, k=$k, $threads threads" >&2
  if [ "$r" -eq 1 ]; then
    "$build/bench/bench_features" --points "$points" --k "$k" --threads "$threads" --write "$cloud" > "$out/ours.txt"
  else
    "$build/bench/bench_features" --points "$points" --k "$k" --threads "$threads" > "$out/ours.txt"
  fi
  grep BENCH_TOTAL_SECONDS "$out/ours.txt" | awk '{print $2}' >> "$out/ours_all.txt"
  if [ -x "$pcl" ]; then
    echo "== round $r/$rounds: PCL NormalEstimationOMP on the same file" >&2
    "$pcl" "$cloud" "$k" "$threads" 1 > "$out/pcl.txt"
    grep PCL_NORMALS_SECONDS "$out/pcl.txt" | awk '{print $2}' >> "$out/pcl_all.txt"
  fi
  echo "== round $r/$rounds: Open3D estimate_normals on the same file" >&2
  OMP_NUM_THREADS=$threads /usr/bin/python3 bench/open3d_normals.py "$cloud" "$k" 1 > "$out/open3d.txt"
  grep OPEN3D_NORMALS_SECONDS "$out/open3d.txt" | awk '{print $2}' >> "$out/open3d_all.txt"
done
median() { sort -g "$1" | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
cat "$out/ours.txt" >&2

echo "== end to end: pointnpr features (read PLY, compute, write PLY), peak memory" >&2
/usr/bin/time -v "$build/pointnpr" features "$cloud" -o "$out/scene_features.ply" --quiet --k "$k" 2> "$out/time.txt"
wall=$(grep "Elapsed (wall clock)" "$out/time.txt" | awk '{print $NF}')
rss=$(grep "Maximum resident set size" "$out/time.txt" | awk '{print $NF}')

ours=$(median "$out/ours_all.txt")
bpp=$(grep BENCH_BYTES_PER_POINT "$out/ours.txt" | awk '{print $2}')
o3d=$(median "$out/open3d_all.txt")
o3dv=$(grep OPEN3D_VERSION "$out/open3d.txt" | awk '{print $2}')
ratio=$(awk -v a="$o3d" -v b="$ours" 'BEGIN { printf "%.2f", a / b }')
e2e_bpp=$(awk -v r="$rss" -v n="$points" 'BEGIN { printf "%.0f", r * 1024 / n }')
{
  echo "Machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); $(date -u +%Y-%m-%d); every side on $threads threads"
  echo
  echo "Stage times of the last round:"
  echo
  sed -n '/^| stage/,/^$/p' "$out/ours.txt"
  echo "| comparison | value |"
  echo "|---|---|"
  echo "| our whole features pipeline (7 stages, in memory), median of $rounds | $ours s ($(paste -sd' ' "$out/ours_all.txt")) |"
  echo "| Open3D $o3dv estimate_normals (KNN $k) alone, median of $rounds | $o3d s ($(paste -sd' ' "$out/open3d_all.txt")) |"
  echo "| speed-up (Open3D normals / our whole pipeline) | **${ratio}x** |"
  if [ -s "$out/pcl_all.txt" ]; then
    pclm=$(median "$out/pcl_all.txt")
    echo "| PCL $(grep PCL_VERSION "$out/pcl.txt" | awk '{print $2}') NormalEstimationOMP (KNN $k) alone, median of $rounds | $pclm s ($(paste -sd' ' "$out/pcl_all.txt")) |"
    echo "| speed-up (PCL normals / our whole pipeline) | **$(awk -v a="$pclm" -v b="$ours" 'BEGIN { printf "%.2f", a / b }')x** |"
  else
    echo "| PCL NormalEstimationOMP | not built (libpcl-dev missing: packaging/deps/segment.bench.txt) |"
  fi
  echo "| peak memory, pipeline in memory (cloud + pipeline) | $bpp bytes/point |"
  echo "| \`pointnpr features\` end to end (read + compute + write PLY): wall | $wall |"
  echo "| \`pointnpr features\` end to end: peak RSS | $((rss / 1024)) MB = $e2e_bpp bytes/point |"
} > "$out/features.md"
cat "$out/features.md"

echo "== profile lines: scaling 10k..1M directional points" >&2
"$build/bench/bench_lines" 1000000 | tee "$out/lines.md"

echo "== the sample by a camera path's views: cost a point (docs/tiles.md)" >&2
"$build/bench/bench_view_sample" 4000000 | tee "$out/view_sample.md"

echo "== a view of a cloud larger than its limit, from the file as written and ordered for drawing (bench/lod.sh)" >&2
bash bench/lod.sh "$build" "$out/lod" | tee "$out/lod.md"

echo "== a view's sample of the ordered file against the uniform sample (bench/bench_lod_view.c)" >&2
"$build/bench/bench_lod_view" "$out/lod/scene_20000000_lod.ply" 1000000 | tee "$out/lod_view.md"

echo "== normals at growing coordinate offsets: Open3D (ours: tests/test_stability)" >&2
/usr/bin/python3 bench/open3d_offset.py 20000 | tee "$out/open3d_offset.md"

echo "== segmentation: ours vs PCL RegionGrowingRGB on generated scenes with known labels" >&2
mkdir -p "$out/segment"
"$build/bench/segment/bench_segment" "$out/segment" 0.005 | tee "$out/segment.md"
if [ -x "$build/bench/segment/segment_pcl" ]; then
  for scene in clean noisy; do
    timeout 600 "$build/bench/segment/segment_pcl" "$out/segment/scene_$scene.bin" | tee -a "$out/segment.md" ||
      echo "| $scene | PCL RegionGrowingRGB | did not finish within 600 s |" | tee -a "$out/segment.md"
  done
fi

echo "== error against run time: pointnpr bench accuracy" >&2
"$build/pointnpr" bench accuracy --out "$out/accuracy" | tee "$out/accuracy.md"

echo "== segment-specific image-space effects: 1M labelled points at 1920x1080 (bench/effects.sh)" >&2
if [ -x "$build/bench/effects_scene" ] && [ -x "$build/pointnpr" ]; then
  bash bench/effects.sh "$build" "$out/effects" | tee "$out/effects.md"
fi

# On a machine with a GPU the headless context takes it (EGL's device platform, render.h): frames/s
# per style at 1.4M and 50M points (issue 18). bench_render prints the GL renderer it drew with.
echo "== renderer on a GPU: frames/s per style at 1.4M and 50M points (skipped on llvmpipe)" >&2
probe=$("$build/render/bench_render" --points 1000 --frames 1 2>/dev/null | grep '^cloud:' || true)
if [ -n "$probe" ] && ! grep -q llvmpipe <<< "$probe"; then
  : > "$out/gpu.md"
  for n in 1400000 50000000; do
    "$build/render/bench_render" --points "$n" --frames 10 > "$out/gpu_$n.txt"
    cat "$out/gpu_$n.txt" >> "$out/gpu.md"
    { echo; echo "| style, $n points | frames/s |"; echo "|---|---:|"
      awk -F'|' '/^\| [a-z]/ && $5 + 0 > 0 { printf "|%s| %.1f |\n", $2, 1000 / $5 }' "$out/gpu_$n.txt"; echo; } | tee -a "$out/gpu.md"
  done
else
  echo "no GPU context (${probe:-no GL}): skipped" | tee "$out/gpu.md"
fi
