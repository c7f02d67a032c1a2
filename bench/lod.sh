#!/usr/bin/env bash
# make bench: a view of a cloud larger than its memory limit, drawn from the file as written and
# from the same file ordered for drawing (convert --lod), in the same run, taking turns (docs/tiles.md,
# "A file ordered for drawing"). Prints a markdown table: wall time and peak of each render, the
# points of the sample, the share of the ordered file read, and the ratio.
#   bash bench/lod.sh BUILD_DIR OUT_DIR [POINTS] [LIMIT]
set -euo pipefail
build=${1:?usage: lod.sh BUILD_DIR OUT_DIR [POINTS] [LIMIT]}
out=${2:?}
points=${3:-20000000}
limit=${4:-600M}
mkdir -p "$out"
plain=$out/scene_$points.ply ordered=$out/scene_${points}_lod.ply
[ -s "$plain" ] || "$build/bench/bench_features" --points "$points" --write "$plain" --write-only > /dev/null
/usr/bin/time -f "%e %M" -o "$out/lod_convert.txt" "$build/pointnpr" convert "$plain" -o "$ordered" --lod --quiet
view=(--size 1280x720 --style points --eye -9,-9,1.5 --target 0,0,0.5 --memory-limit "$limit")
: > "$out/lod_runs.txt"
for round in 1 2 3; do
  for f in "$plain" "$ordered"; do
    /usr/bin/time -f "%e %M" -o "$out/lod_time.txt" "$build/pointnpr" render "$f" -o "$out/lod_view.png" "${view[@]}" 2> "$out/lod_log.txt" ||
      { echo "render of $f failed:" >&2; cat "$out/lod_log.txt" >&2; exit 1; }
    kept=$(sed -n 's/.* of \([0-9]*\) (\([0-9.]*\)%.*/\1/p' "$out/lod_log.txt" | head -n 1)
    read_pc=$(sed -n 's/.*ordered for drawing: \([0-9.]*\)% of its points read.*/\1/p' "$out/lod_log.txt")
    echo "$(basename "$f") $(cat "$out/lod_time.txt") ${kept:-?} ${read_pc:--}" >> "$out/lod_runs.txt"
  done
done
median() { awk -v f="$1" -v c="$2" '$1 == f { print $c }' "$out/lod_runs.txt" | sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
a=$(median "$(basename "$plain")" 2) b=$(median "$(basename "$ordered")" 2)
echo "Machine: $(nproc) cores, $(date -u +%Y-%m-%d); $points generated points, a view at 1280x720 (points), --memory-limit $limit"
echo
echo "| file | render wall, median of 3 | peak | sample | read |"
echo "|---|---:|---:|---:|---:|"
for f in "$plain" "$ordered"; do
  n=$(basename "$f")
  echo "| $n | $(median "$n" 2) s | $(( $(median "$n" 3) / 1024 )) MiB | $(median "$n" 4) | $(median "$n" 5) % |"
done
echo "| ratio (as written / ordered) | **$(awk -v a="$a" -v b="$b" 'BEGIN { printf "%.2f", a / b }')x** | | | |"
echo
echo "\`convert --lod\`: $(awk '{ printf "%s s, peak %d MiB", $1, $2 / 1024 }' "$out/lod_convert.txt")"
