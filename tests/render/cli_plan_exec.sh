#!/usr/bin/env bash
# The plan is what runs: for every style of the library and four kinds of input (coloured,
# colourless, with segment labels, with saved features), the analysis stages `pointnpr render`
# announces are exactly the ones `pointnpr explain` on the same file and style marks "run"
# (issue 17: the plan printed equals the plan executed).
#   bash cli_plan_exec.sh /path/to/pointnpr SCRATCH_DIR        (exit 77: no headless GL here)
set -uo pipefail
bin=$1
dir=$2/cli_plan_exec
rm -rf "$dir"; mkdir -p "$dir"
fail=0

# a sampled cube (spacing 0.05): coloured, colourless, with labels (two halves)
cube() { # $1: extra header lines, $2: per-point format of the extra columns (awk), $3: out
  awk -v hdr="$1" -v fmt="$2" 'BEGIN {
    m = 12; h = 0.05; n = 0
    for (i = 0; i <= m; i++) for (j = 0; j <= m; j++) for (k = 0; k <= m; k++) {
      if (i > 0 && i < m && j > 0 && j < m && k > 0 && k < m) continue
      extra = fmt == "rgb" ? sprintf(" %d %d %d", 200, 100 + i * 10, 50) : fmt == "label" ? sprintf(" %d %d %d %d", 200, 100 + i * 10, 50, i < m / 2) : ""
      line[n++] = sprintf("%.9g %.9g %.9g%s", i * h, j * h, k * h, extra)
    }
    print "ply"; print "format ascii 1.0"; print "element vertex " n
    print "property float x"; print "property float y"; print "property float z"
    if (hdr != "") print hdr
    print "end_header"
    for (q = 0; q < n; q++) print line[q]
  }' > "$3"
}
rgb_hdr=$'property uchar red\nproperty uchar green\nproperty uchar blue'
cube "$rgb_hdr" rgb "$dir/coloured.ply"
cube "" none "$dir/colourless.ply"
cube "$rgb_hdr"$'\nproperty int label' label "$dir/labelled.ply"
"$bin" features "$dir/coloured.ply" -o "$dir/featured.ply" > /dev/null 2>&1 || { echo "FAILED: features" >&2; exit 1; }

# the library's styles, from its own message
styles=$("$bin" render "$dir/coloured.ply" -o "$dir/x.png" --style nosuch 2>&1 | sed -n "s/.*wants one of \(.*\), got.*/\1/p" | tr -d ',')
[ -n "$styles" ] || { echo "FAILED: no style list in the --style message" >&2; exit 1; }

# explain's rows that render announces, and render's announcement of each
planned() { # the stages explain marks "run", one per line, in render's words
  "$bin" explain "$1" --style "$2" | awk '
    /^  kd-tree \+ knn +run /     { print "features" }
    /^  profile lines +run /      { print "lines" }
    /^  segments +run /           { print "segments" }
    /^  brush sizes +run /        { print "brush" }
    /^  sphere hierarchy +run /   { print "hierarchy" }'
}
executed() { # the stages render announces on stderr, one per line
  "$bin" render "$1" --style "$2" -o "$dir/out.png" --size 64x48 2>&1 >/dev/null | awk '
    /: computing (features|normals)/             { print "features" }
    /: [0-9]+ profile lines/                     { print "lines" }
    /: segmenting the colours/                   { print "segments" }
    /: preparing the brush strokes/              { print "brush" }
    /: building the sphere hierarchy/            { print "hierarchy" }'
}

n=0
for in in coloured colourless labelled featured; do
  for s in $styles; do
    p=$(planned "$dir/$in.ply" "$s" | sort | tr '\n' ' ')
    e=$(executed "$dir/$in.ply" "$s" | sort | tr '\n' ' ')
    if [ "$p" != "$e" ]; then
      echo "FAILED: $in.ply --style $s: explain plans [${p}], render runs [${e}]" >&2
      fail=1
    fi
    n=$((n + 1))
  done
done
# the comparison has teeth: some combination plans something, and not every one plans the same
all=$(for in in coloured colourless; do for s in $styles; do planned "$dir/$in.ply" "$s"; done; done | sort -u | tr '\n' ' ')
[ "$all" = "brush features hierarchy lines segments " ] || { echo "FAILED: the stages planned over all styles: [$all]" >&2; fail=1; }
[ -z "$(planned "$dir/featured.ply" sketchy)" ] || { echo "FAILED: saved features are not reused for sketchy" >&2; fail=1; }
echo "$n style x input combinations: explain's plan = what render ran"
exit $fail
