#!/usr/bin/env bash
# MeshLab plugin tests: runs the filters of libfilter_pointnpr.so inside Debian's meshlabserver.
#
#   tests/meshlab/run.sh TEST PLUGIN_SO POINTNPR_CLI WORKDIR [DECORATE_SO]
#     TEST: load | cube | offset | select | robust | lion | lines | segment | sample | decorate | decorate_styles | snapshot | stream
#     DECORATE_SO: libdecorate_pointnpr.so ("NPR render"), also put into the host's plugins/;
#     the decorate test runs the MeshLab GUI (/usr/bin/meshlab) under Xvfb.
#
# meshlabserver runs from a private folder WORKDIR/TEST/host holding a hard link (or copy) of the
# binary and plugins/ with symlinks to the system plugins plus ours (MeshLab only looks for
# plugins next to its binary), with LD_LIBRARY_PATH=/usr/lib/x86_64-linux-gnu/meshlab, under an
# Xvfb server that this script starts on a free display and stops on exit (meshlabserver needs a
# display even for non-GL filters). Outputs are saved as binary PLY and turned into ascii by
# `pointnpr convert --ascii` so that awk can check the numbers.
set -uo pipefail

TEST=${1:?usage: run.sh TEST PLUGIN_SO POINTNPR_CLI WORKDIR}
PLUGIN=${2:?}
CLI=${3:?}
WORK=${4:?}
DECORATE=${5:-}
GUI_BIN=${PNPR_MESHLAB_GUI:-/usr/bin/meshlab}
HERE=$(cd "$(dirname "$0")" && pwd)
SRC=$(cd "$HERE/../.." && pwd)
MLLIB=${PNPR_MESHLAB_LIBDIR:-/usr/lib/x86_64-linux-gnu/meshlab}
SERVER_BIN=${PNPR_MESHLABSERVER:-/usr/bin/meshlabserver}
T="$WORK/$TEST"
XVFB_PID=""
FAILS=0

log() { echo "[$TEST] $*"; }
fail() { echo "[$TEST] FAIL: $*"; FAILS=$((FAILS + 1)); }
die() { echo "[$TEST] FAIL: $*"; exit 1; }
cleanup() { if [[ -n "$XVFB_PID" ]]; then kill "$XVFB_PID" 2> /dev/null; wait "$XVFB_PID" 2> /dev/null; fi; }
trap cleanup EXIT

rm -rf "$T"
mkdir -p "$T/host/plugins" || die "cannot create $T"

# ---- private MeshLab host ----
setup_host() {
  [[ -x "$SERVER_BIN" ]] || die "$SERVER_BIN not found (packaging/install-deps.sh installs meshlab)"
  [[ -f "$PLUGIN" ]] || die "plugin $PLUGIN not built"
  ln "$SERVER_BIN" "$T/host/meshlabserver" 2> /dev/null || cp "$SERVER_BIN" "$T/host/meshlabserver" ||
    die "cannot copy $SERVER_BIN"
  local p
  for p in "$MLLIB"/plugins/*.so; do
    [[ "$(basename "$p")" == lib*_pointnpr.so ]] && continue # an installed older copy
    ln -s "$p" "$T/host/plugins/"
  done
  ln -s "$(cd "$(dirname "$PLUGIN")" && pwd)/$(basename "$PLUGIN")" "$T/host/plugins/libfilter_pointnpr.so"
  if [[ -n "$DECORATE" ]]; then
    [[ -f "$DECORATE" ]] || die "plugin $DECORATE not built"
    ln -s "$(cd "$(dirname "$DECORATE")" && pwd)/$(basename "$DECORATE")" "$T/host/plugins/libdecorate_pointnpr.so"
  fi
}

# ---- Xvfb on a free display ----
start_xvfb() {
  command -v Xvfb > /dev/null || die "Xvfb not installed (packaging/install-deps.sh installs xvfb)"
  local d tries
  for d in $(seq $((100 + RANDOM % 300)) 500); do
    [[ -e /tmp/.X$d-lock || -e /tmp/.X11-unix/X$d ]] && continue
    Xvfb ":$d" -nolisten tcp -screen 0 1280x1024x24 > "$T/xvfb.log" 2>&1 &
    XVFB_PID=$!
    for tries in $(seq 1 50); do
      if [[ -e /tmp/.X11-unix/X$d ]]; then export DISPLAY=":$d"; return 0; fi
      kill -0 "$XVFB_PID" 2> /dev/null || break
      sleep 0.1
    done
    kill "$XVFB_PID" 2> /dev/null; wait "$XVFB_PID" 2> /dev/null; XVFB_PID=""
  done
  die "could not start Xvfb (log: $T/xvfb.log)"
}

# mlserver NAME ARGS...: runs meshlabserver, output in $T/NAME.log, exit status in $T/NAME.rc;
# fails the test on a crash (signal, abort, segfault), never on the filter's own error.
mlserver() {
  local name=$1; shift
  local start end rc
  start=$(date +%s.%N)
  (cd "$T" && LD_LIBRARY_PATH="$MLLIB${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" timeout 240 \
      "$T/host/meshlabserver" "$@") > "$T/$name.log" 2>&1
  rc=$?
  end=$(date +%s.%N)
  echo "$rc" > "$T/$name.rc"
  awk -v s="$start" -v e="$end" 'BEGIN { printf "%.2f\n", e - s }' > "$T/$name.secs"
  # 255 = meshlabserver's own exit(-1) after a failed filter (a reported error, not a crash);
  # 124 = timeout; 128+N = killed by signal N (segfault, abort)
  if ((rc == 124 || (rc >= 128 && rc < 255))) || grep -qE "Segmentation fault|Aborted|core dumped|terminate called|Assertion .* failed" "$T/$name.log"; then
    fail "meshlabserver crashed or hung in '$name' (exit $rc); log:"
    tail -n 20 "$T/$name.log"
    return 1
  fi
  return 0
}

# float_offset_cube: MeshLab stores float coordinates. The unit cube (h = 0.02) at the offset test's
# (1e7, -1e7, 5e6), in a file of doubles: MeshLab rounds it to the float step there (1 at 1e7,
# 0.5 at 5e6) when it loads it; the plugin must say so with the figures and the remedies. The
# pointnpr command reads the doubles and finds the cube's edges; MeshLab's layer has lost them,
# and moving the layer to the origin afterwards (Transform: Translate, Center, set Origin, frozen)
# does not bring them back (the warning's advice). Rounded positions: x in {1e7, 1e7+1}, y in
# {-1e7, -1e7+1}, z in {5e6, 5e6+0.5, 5e6+1}: 2 x 2 x 3 = 12 distinct positions (all on the
# cube's surface, x being 0 or 1), each 0.5 from its z neighbour.
float_offset_cube() {
  cube_ply "$T/unit.ply" 1 50 10000000 -10000000 5000000 double
  mlx "$T/u.mlx" "$(features_xml)"
  mlserver unit -i "$T/unit.ply" -o "$T/unit-out.ply" -m vq -s "$T/u.mlx" && expect_rc unit 0
  expect_log unit "LOG: 1 pointnpr: WARNING: layer 'unit.ply' lies up to 10000001 from the origin, where MeshLab's float coordinates step by 1; its 15002 points sit on 12 distinct positions, a median 0.5 apart \\(0.5 times the step\\): MeshLab keeps positions only to that step \\(finer coordinates in the file were rounded when it was loaded\\), so the features are unreliable"
  expect_log unit "Moving the layer now \\(Filters > Normals, Curvatures and Orientation > Transform: Translate, Center, set Origin\\) cannot restore them: move the data near the origin before MeshLab loads it, or run the pointnpr command on the file \\(it keeps double coordinates\\)"
  grep -o "pointnpr: WARNING.*" "$T/unit.log" | head -n 1
  local ml cli moved
  ml=$(sed -n 's/.*pointnpr: \([0-9]*\) feature points.*/\1/p' "$T/unit.log" | head -n 1)
  "$CLI" features "$T/unit.ply" -o "$T/unit-cli.ply" --ascii --quiet || fail "pointnpr features on unit.ply failed"
  cli=$(awk '/^property/ && !b { col[$NF] = np++ } /^end_header/ { b = 1; next }
             b { c = $(col["feature_class"] + 1); if (c == 1 || c == 2) n++ } END { print n + 0 }' "$T/unit-cli.ply")
  # translate to the layer's centre, frozen into the vertices, then the features: no warning left
  # (the coordinates are small now), and still no edges
  mlx "$T/t.mlx" ' <filter name="Transform: Translate, Center, set Origin">
  <Param type="RichEnum" name="traslMethod" value="2" enum_cardinality="4" enum_val0="XYZ translation" enum_val1="Center on Scene BBox" enum_val2="Center on Layer BBox" enum_val3="Set new Origin"/>
  <Param type="RichDynamicFloat" name="axisX" value="0" min="-10" max="10"/>
  <Param type="RichDynamicFloat" name="axisY" value="0" min="-10" max="10"/>
  <Param type="RichDynamicFloat" name="axisZ" value="0" min="-10" max="10"/>
  <Param type="RichPoint3f" name="newOrigin" x="0" y="0" z="0"/>
  <Param type="RichBool" name="Freeze" value="true"/>
  <Param type="RichBool" name="allLayers" value="false"/>
 </filter>' "$(features_xml)"
  mlserver moved -i "$T/unit.ply" -o "$T/moved-out.ply" -m vq -s "$T/t.mlx" && expect_rc moved 0
  expect_no_log moved "pointnpr: WARNING"
  moved=$(sed -n 's/.*pointnpr: \([0-9]*\) feature points.*/\1/p' "$T/moved.log" | head -n 1)
  log "unit cube at 1e7: feature points: pointnpr command $cli, MeshLab $ml, MeshLab after moving the layer to the origin $moved"
  holds unit "the pointnpr command finds the cube's edges (540 edge points)" "$cli >= 300"
  holds unit "MeshLab's rounded layer has lost them" "${ml:-999999} * 10 < $cli && ${moved:-999999} * 10 < $cli"
  # the rule's edge (a spacing of 8 float steps), on cubes of integer coordinates: h = 7 warns,
  # h = 9 does not (the side-1000 cube above, h = 20, does not either)
  cube_ply "$T/h7.ply" 350 50 10000000 -10000000 5000000
  cube_ply "$T/h9.ply" 450 50 10000000 -10000000 5000000
  mlserver h7 -i "$T/h7.ply" -o "$T/h7-out.ply" -m vq -s "$T/u.mlx" && expect_rc h7 0
  expect_log h7 "WARNING: layer 'h7.ply' lies up to 10000350 from the origin, where MeshLab's float coordinates step by 1; its 15002 points sit on 15002 distinct positions, a median 7 apart \\(7 times the step\\)"
  mlserver h9 -i "$T/h9.ply" -o "$T/h9-out.ply" -m vq -s "$T/u.mlx" && expect_rc h9 0
  expect_no_log h9 "pointnpr: WARNING"
}

# ---- inputs ----
# cube_ply OUT SIDE STEPS OX OY OZ [TYPE]: the surface of the cube [0,SIDE]^3 + (OX,OY,OZ) sampled on
# a grid of STEPS+1 points per edge (no duplicates), ascii PLY, positions only, of TYPE (float;
# double keeps the exact positions in the file).
cube_ply() {
  awk -v n="$3" -v s="$2" -v ox="$4" -v oy="$5" -v oz="$6" -v t="${7:-float}" 'BEGIN {
    c = (n + 1) ^ 3 - (n - 1) ^ 3
    printf "ply\nformat ascii 1.0\nelement vertex %d\nproperty %s x\nproperty %s y\nproperty %s z\nend_header\n", c, t, t, t
    for (i = 0; i <= n; i++) for (j = 0; j <= n; j++) for (k = 0; k <= n; k++) {
      if (i > 0 && i < n && j > 0 && j < n && k > 0 && k < n) continue
      printf "%.10g %.10g %.10g\n", ox + s * i / n, oy + s * j / n, oz + s * k / n
    }
  }' > "$1"
}

# mlx OUT FILTER_XML...: a filter script
mlx() {
  local out=$1; shift
  { echo '<!DOCTYPE FilterScript>'; echo '<FilterScript>'; printf '%s\n' "$@"; echo '</FilterScript>'; } > "$out"
}
# features_xml [name=value ...]: the compute filter with every parameter (defaults overridable)
features_xml() {
  local k=16 threshold=0 wg=0.5 wc=0.5 conf=0.6 dither=1 recompute=false usevp=false vx=0 vy=0 vz=0 color=false kv
  for kv in "$@"; do local "$kv"; done
  cat << EOF
 <filter name="NPR: Compute feature degree and classify points">
  <Param type="RichInt" name="k" value="$k"/>
  <Param type="RichFloat" name="threshold" value="$threshold"/>
  <Param type="RichFloat" name="weightGeometry" value="$wg"/>
  <Param type="RichFloat" name="weightColor" value="$wc"/>
  <Param type="RichFloat" name="directionConfidence" value="$conf"/>
  <Param type="RichFloat" name="ditherScale" value="$dither"/>
  <Param type="RichBool" name="recomputeNormals" value="$recompute"/>
  <Param type="RichBool" name="useViewpoint" value="$usevp"/>
  <Param type="RichPoint3f" name="viewpoint" x="$vx" y="$vy" z="$vz"/>
  <Param type="RichBool" name="colorByClass" value="$color"/>
 </filter>
EOF
}
# select_xml CLASS ADD: CLASS 0 directional, 1 non-directional, 2 any feature, 3 dithering
select_xml() {
  cat << EOF
 <filter name="NPR: Select feature points">
  <Param type="RichEnum" name="featureClass" value="$1" enum_cardinality="4" enum_val0="Directional feature points" enum_val1="Non-directional feature points" enum_val2="Any feature point" enum_val3="Dithering points"/>
  <Param type="RichBool" name="addToSelection" value="${2:-false}"/>
 </filter>
EOF
}

# lines_xml [name=value ...]: the profile-lines filter with every parameter
lines_xml() {
  local spacing=0 radius=0 merge=0 minlen=0 beta=4 shifts=4 corners=true recompute=false k=16 threshold=0 conf=0.6 kv
  for kv in "$@"; do local "$kv"; done
  cat << EOF
 <filter name="NPR: Profile lines">
  <Param type="RichFloat" name="spacing" value="$spacing"/>
  <Param type="RichFloat" name="radius" value="$radius"/>
  <Param type="RichFloat" name="mergeTolerance" value="$merge"/>
  <Param type="RichFloat" name="minLength" value="$minlen"/>
  <Param type="RichFloat" name="directionWeight" value="$beta"/>
  <Param type="RichInt" name="shiftIterations" value="$shifts"/>
  <Param type="RichBool" name="corners" value="$corners"/>
  <Param type="RichBool" name="recomputeFeatures" value="$recompute"/>
  <Param type="RichInt" name="k" value="$k"/>
  <Param type="RichFloat" name="threshold" value="$threshold"/>
  <Param type="RichFloat" name="directionConfidence" value="$conf"/>
 </filter>
EOF
}
# jseg_xml [name=value ...]: the JSEG filter with every parameter
jseg_xml() {
  local segments=0 hthr=0 classes=16 qd=12 k=24 radius=0 seed=0.6 md=10 minsize=0 color=true quality=true kv
  for kv in "$@"; do local "$kv"; done
  cat << EOF
 <filter name="NPR: Segment (JSEG)">
  <Param type="RichInt" name="segments" value="$segments"/>
  <Param type="RichFloat" name="hierarchyThreshold" value="$hthr"/>
  <Param type="RichInt" name="classes" value="$classes"/>
  <Param type="RichFloat" name="quantDistance" value="$qd"/>
  <Param type="RichInt" name="k" value="$k"/>
  <Param type="RichFloat" name="radius" value="$radius"/>
  <Param type="RichFloat" name="seedFactor" value="$seed"/>
  <Param type="RichFloat" name="mergeDistance" value="$md"/>
  <Param type="RichInt" name="minSize" value="$minsize"/>
  <Param type="RichBool" name="colorBySegment" value="$color"/>
  <Param type="RichBool" name="labelToQuality" value="$quality"/>
 </filter>
EOF
}
# grow_xml [name=value ...]: components (method=0) / colour region growing (method=1)
grow_xml() {
  local method=0 distance=0 minsize=10 k=16 pcd=25 rcd=10 color=false quality=true kv
  for kv in "$@"; do local "$kv"; done
  cat << EOF
 <filter name="NPR: Segment (connected components / colour region growing)">
  <Param type="RichEnum" name="method" value="$method" enum_cardinality="2" enum_val0="Connected components" enum_val1="Colour region growing"/>
  <Param type="RichFloat" name="distance" value="$distance"/>
  <Param type="RichInt" name="minSize" value="$minsize"/>
  <Param type="RichInt" name="k" value="$k"/>
  <Param type="RichFloat" name="pointColorDistance" value="$pcd"/>
  <Param type="RichFloat" name="regionColorDistance" value="$rcd"/>
  <Param type="RichBool" name="colorBySegment" value="$color"/>
  <Param type="RichBool" name="labelToQuality" value="$quality"/>
 </filter>
EOF
}

# check_cube_lines OBJ SIDE H OX OY OZ: profile lines of the cube [0,SIDE]^3 + (OX,OY,OZ) saved as
# OBJ (v + l): >= 12 polylines (connected components of the edge graph; the plugin gives every
# polyline its own vertices), every vertex within 2h of a cube edge, total edge length within 10%
# of 12 x SIDE, no vertex without an edge.
check_cube_lines() {
  awk -v s="$2" -v h="$3" -v ox="$4" -v oy="$5" -v oz="$6" '
    function absv(v) { return v < 0 ? -v : v }
    function find(a) { while (par[a] != a) { par[a] = par[par[a]]; a = par[a] } return a }
    $1 == "v" { nv++; x[nv] = $2 - ox; y[nv] = $3 - oy; z[nv] = $4 - oz; par[nv] = nv }
    $1 == "l" { for (i = 2; i < NF; i++) { a = $i + 0; b = $(i + 1) + 0; ne++; used[a] = used[b] = 1
                  len += sqrt((x[a] - x[b]) ^ 2 + (y[a] - y[b]) ^ 2 + (z[a] - z[b]) ^ 2)
                  ra = find(a); rb = find(b); if (ra != rb) par[ra] = rb } }
    END {
      for (v = 1; v <= nv; v++) {
        d[0] = x[v] < s - x[v] ? absv(x[v]) : absv(s - x[v]); d[1] = y[v] < s - y[v] ? absv(y[v]) : absv(s - y[v])
        d[2] = z[v] < s - z[v] ? absv(z[v]) : absv(s - z[v])
        for (a = 0; a < 3; a++) for (b = a + 1; b < 3; b++) if (d[b] < d[a]) { t = d[a]; d[a] = d[b]; d[b] = t }
        e = sqrt(d[0] ^ 2 + d[1] ^ 2); if (e > emax) emax = e; if (e > 2 * h) far++
        if (!used[v]) lonely++; if (find(v) == v) comps++
      }
      printf "lines: %d vertices, %d edges, %d polylines, total length %.4f (12 x side = %g), max distance to an edge %.4g (h = %g), %d vertices farther than 2h, %d without an edge\n",
        nv, ne, comps, len, 12 * s, emax, h, far, lonely
      exit (nv > 0 && comps >= 12 && far == 0 && lonely == 0 && len >= 0.9 * 12 * s && len <= 1.1 * 12 * s) ? 0 : 1
    }' "$1"
}

# ari_awk: lines "TRUTH RESULT" -> "ARI TRUTH_SEGMENTS RESULT_SEGMENTS" (adjusted Rand index, Hubert & Arabie)
ari_awk() {
  awk '{ n++; nij[$1 SUBSEP $2]++; a[$1]++; b[$2]++ }
    function c2(v) { return v * (v - 1) / 2 }
    END { for (k in nij) sij += c2(nij[k]); for (k in a) { sa += c2(a[k]); na++ } for (k in b) { sb += c2(b[k]); nb++ }
          e = sa * sb / c2(n); mx = (sa + sb) / 2
          printf "%.4f %d %d\n", (mx == e ? 1 : (sij - e) / (mx - e)), na, nb }'
}

# scene_ply OUT.ply TRUTH SEED: the library test scene (tests/test_segment.c make_scene, clean:
# spacing 0.02, position noise 0.001, colour noise 4): grey ground plane, red box on it, blue
# sphere touching the box, green cylinder touching its other side; TRUTH gets "x y z object" per
# point in file order.
scene_ply() {
  awk -v seed="$3" -v truth="$2" 'function nrm() { return sqrt(-2 * log(1 - rand())) * cos(6.283185307179586 * rand()) }
    function add(x, y, z, r, g, b, o,   c) {
      px[N] = x + 0.001 * nrm(); py[N] = y + 0.001 * nrm(); pz[N] = z + 0.001 * nrm()
      c = r + 4 * nrm(); cr[N] = c < 0 ? 0 : (c > 255 ? 255 : int(c + 0.5))
      c = g + 4 * nrm(); cg[N] = c < 0 ? 0 : (c > 255 ? 255 : int(c + 0.5))
      c = b + 4 * nrm(); cb[N] = c < 0 ? 0 : (c > 255 ? 255 : int(c + 0.5))
      obj[N] = o; N++ }
    BEGIN { srand(seed); h = 0.02; PI = 3.14159265358979323846
      for (x = -1; x <= 1 + 1e-9; x += h) for (y = -1; y <= 1 + 1e-9; y += h) {
        if (x > -0.5 && x < 0.1 && y > -0.3 && y < 0.3) continue
        add(x, y, 0, 140, 140, 140, 0) }
      m = int(0.6 / h + 0.5)
      for (i = 0; i <= m; i++) for (j = 0; j <= m; j++) {
        u = -0.5 + 0.6 * i / m; v = 0.6 * j / m; w = -0.3 + 0.6 * i / m
        if (j > 0) { add(u, -0.3, v, 200, 40, 40, 1); add(u, 0.3, v, 200, 40, 40, 1)
                     if (i > 0 && i < m) { add(-0.5, w, v, 200, 40, 40, 1); add(0.1, w, v, 200, 40, 40, 1) } }
        if (i > 0 && i < m && j > 0 && j < m) add(u, -0.3 + 0.6 * j / m, 0.6, 200, 40, 40, 1) }
      r = 0.35; ns = int(4 * PI * r * r / (h * h))
      for (i = 0; i < ns; i++) { z = 1 - 2 * (i + 0.5) / ns; rr = sqrt(1 - z * z); phi = i * PI * (3 - sqrt(5))
        add(0.45 + h + r * rr * cos(phi), r * rr * sin(phi), 0.35 + r * z, 40, 60, 200, 2) }
      cr0 = 0.2; nr = int(2 * PI * cr0 / h); nz = int(0.8 / h)
      for (a = 0; a < nr; a++) for (b = 1; b <= nz; b++) { t = 2 * PI * a / nr
        add(-0.2 + cr0 * cos(t), 0.5 + h + cr0 * sin(t), 0.8 * b / nz, 40, 170, 60, 3) }
      for (x = -cr0; x <= cr0; x += h) for (y = -cr0; y <= cr0; y += h)
        if (x * x + y * y < (cr0 - h / 2) ^ 2) add(-0.2 + x, 0.5 + h + y, 0.8, 40, 170, 60, 3)
      printf "ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n", N
      for (i = 0; i < N; i++) { printf "%.7g %.7g %.7g %d %d %d\n", px[i], py[i], pz[i], cr[i], cg[i], cb[i]
                                printf "%.7g %.7g %.7g %d\n", px[i], py[i], pz[i], obj[i] > truth } }' > "$1"
}

# score_segments OUT-ASCII.ply TRUTH WHAT MIN_ARI [SEGMENTS]: ARI of the labels saved in vertex
# quality and of the colours against the truth (file order; positions must match the truth file);
# with SEGMENTS the label count must equal it. Labels must be integers 0..S-1.
score_segments() {
  local out=$1 truth=$2 what=$3 min=$4 want=${5:-0} q c qa qt qs ca cs
  awk '/^property/ && !b { col[$NF] = np++ } /^end_header/ { b = 1; next }
    b { printf "%s %s %s %s %s,%s,%s\n", $(col["x"] + 1), $(col["y"] + 1), $(col["z"] + 1), $(col["quality"] + 1),
        $(col["red"] + 1), $(col["green"] + 1), $(col["blue"] + 1) }' "$out" > "$T/scored.txt"
  if ! awk 'NR == FNR { tx[FNR] = $1; ty[FNR] = $2; tz[FNR] = $3; n = FNR; next }
      { m++; d = ($1 - tx[FNR]) ^ 2 + ($2 - ty[FNR]) ^ 2 + ($3 - tz[FNR]) ^ 2; if (d > 1e-8) bad++
        if ($4 != int($4) || $4 < 0) badl++; if ($4 + 1 > S) S = $4 + 1; seen[$4] = 1 }
      END { for (l in seen) k++; if (bad || m != n || badl || k != S) { printf "order/labels: %d of %d points moved, %d non-integer labels, %d labels used of 0..%d\n", bad, n, badl, k, S - 1; exit 1 } }' \
      "$truth" "$T/scored.txt"; then
    fail "$what: output does not line up with the ground truth or labels are not 0..S-1"; return 1
  fi
  q=$(paste -d ' ' <(awk '{ print $4 }' "$truth") <(awk '{ print $4 }' "$T/scored.txt") | ari_awk)
  c=$(paste -d ' ' <(awk '{ print $4 }' "$truth") <(awk '{ print $5 }' "$T/scored.txt") | ari_awk)
  read -r qa qt qs <<< "$q"; read -r ca _ cs <<< "$c"
  log "$what: ARI of the labels $qa ($qs segments, truth $qt), ARI of the colours $ca ($cs colours)"
  awk -v a="$qa" -v m="$min" 'BEGIN { exit a >= m ? 0 : 1 }' || fail "$what: label ARI $qa < $min"
  [[ "$want" == 0 || "$qs" == "$want" ]] || fail "$what: $qs segments, expected $want"
  LAST_SCORE="$qa $qs $ca $cs"
}

# to_ascii IN.ply OUT.ply: MeshLab's binary PLY -> ascii through the project's own reader/writer
to_ascii() { "$CLI" convert "$1" -o "$2" --ascii --quiet || { fail "pointnpr convert $1 failed"; return 1; }; }

# check_cube PLY SIDE H OX OY OZ: known answers on a cube filtered with colorByClass + select
# directional. Colours encode the class (palette in filter_pointnpr.cpp), the selection flag
# (0x20) must equal "directional", quality = feature degree.
check_cube() {
  awk -v s="$2" -v h="$3" -v ox="$4" -v oy="$5" -v oz="$6" '
    function cls(r, g, b) { if (r == 220 && g == 30 && b == 30) return 2; if (r == 40 && g == 100 && b == 230) return 1;
                            if (r == 20 && g == 20 && b == 20) return 3; if (r == 200 && g == 200 && b == 200) return 0; return -1 }
    function absv(v) { return v < 0 ? -v : v }
    /^element vertex/ { nv = $3 }
    /^property/ && !inbody { col[$NF] = np++ }
    /^end_header/ { inbody = 1; next }
    inbody && nv > 0 {
      nv--
      x = $(col["x"] + 1) - ox; y = $(col["y"] + 1) - oy; z = $(col["z"] + 1) - oz
      q = $(col["quality"] + 1); f = $(col["flags"] + 1)
      c = cls($(col["red"] + 1), $(col["green"] + 1), $(col["blue"] + 1))
      d[0] = x < s - x ? absv(x) : absv(s - x); d[1] = y < s - y ? absv(y) : absv(s - y); d[2] = z < s - z ? absv(z) : absv(s - z)
      # sort the three boundary distances
      for (a = 0; a < 3; a++) for (b = a + 1; b < 3; b++) if (d[b] < d[a]) { t = d[a]; d[a] = d[b]; d[b] = t }
      total++
      if (c < 0) badcolour++
      sel = int(f / 32) % 2
      if (sel != (c == 2)) selmismatch++
      if (d[1] < 1e-6 * s && d[2] >= 3 * h - 1e-6 * s) {          # edge point (3h from corners)
        edge++; eq += q; if (q < 0.2) edgelow++; if (c == 2) edgedir++; if (c == 1 || c == 2) edgefeat++
      } else if (d[1] >= 3 * h - 1e-6 * s) {          # face point (3h from edges)
        face++; fq += q; if (q > fqmax) fqmax = q; if (c == 1 || c == 2) facefeat++
        nx = $(col["nx"] + 1); ny = $(col["ny"] + 1); nz = $(col["nz"] + 1)
        # the face normal is the axis of the boundary coordinate: |component| ~ 1
        ax = absv(x) < 1e-6 * s || absv(s - x) < 1e-6 * s ? absv(nx) : (absv(y) < 1e-6 * s || absv(s - y) < 1e-6 * s ? absv(ny) : absv(nz))
        if (ax < 0.996) badnormal++                   # > 5 degrees off
      } else if (d[2] < 1.5 * h) { corner++; if (c == 2) cornerdir++ }
    }
    END {
      printf "points %d: edge %d (mean quality %.3f, quality<0.2: %d, directional %d, feature %d), face %d (mean quality %.4f, max %.3f, feature %d, normals >5deg off %d), corner %d (directional %d), selection mismatches %d, unknown colours %d\n",
        total, edge, edge ? eq / edge : 0, edgelow, edgedir, edgefeat, face, face ? fq / face : 0, fqmax, facefeat, badnormal, corner, cornerdir, selmismatch, badcolour
      ok = total > 0 && edge > 500 && face > 10000
      ok = ok && eq / edge >= 0.5 && edgelow <= 0.05 * edge           # quality high on edges
      ok = ok && fq / face <= 0.01 && fqmax < 0.15                      # ~0 on faces
      ok = ok && edgefeat >= 0.9 * edge && edgedir >= 0.9 * edge && facefeat <= 0.01 * face && cornerdir == 0
      ok = ok && badnormal == 0 && selmismatch == 0 && badcolour == 0
      exit ok ? 0 : 1
    }' "$1"
}

expect_log() { grep -qE -- "$2" "$T/$1.log" || fail "'$1': expected /$2/ in the output (log: $T/$1.log)"; }
expect_no_log() { ! grep -qE -- "$2" "$T/$1.log" || fail "'$1': unexpected /$2/ in the output: $(grep -E -- "$2" "$T/$1.log" | head -n 1)"; }
expect_rc() { [[ "$(cat "$T/$1.rc")" == "$2" ]] || fail "'$1': exit status $(cat "$T/$1.rc"), expected $2"; }
no_plugin_errors() {
  if grep -iE "pointnpr" "$T/$1.log" | grep -qiE "cannot load|undefined symbol|not a valid|failed to|error"; then
    fail "'$1': plugin load error:"; grep -iE "pointnpr" "$T/$1.log" | head -5
  fi
}

# ---- the decorator in the MeshLab GUI (cases decorate, decorate_styles) ----
# gui NAME STYLE INPUT [SETTING=VALUE ...]: one run of the MeshLab GUI (private host, fresh HOME)
# on INPUT until the decorator's frame pair is written (or 120 s), then MeshLab is stopped.
# Without settings the style comes from the test hook PNPR_MESHLAB_TEST_STYLE=STYLE and MeshLab
# starts with its defaults; with settings the style and every other parameter come from MeshLab's
# settings file as the decorator dialog saves them: BASECONF (an earlier run's file, every
# parameter at its default) with each PointNPR::SETTING's value replaced (enum index or number),
# and the frame must then be drawn in STYLE. Checks: no crash, no plugin load error, the
# decoration enabled, renderer created, 15002 points uploaded, frame pair written.
gui() {
  local name=$1 style=$2 input=$3 pid i kv key val conf
  shift 3
  local -a extra=(PNPR_MESHLAB_TEST_STYLE="$style")
  mkdir -p "$T/home-$name"
  if (($# > 0)); then
    [[ -f "$BASECONF" ]] || { fail "'$name': no base settings file $BASECONF"; return 1; }
    extra=()
    conf="$T/home-$name/.config/VCG/$(basename "$BASECONF")"
    mkdir -p "$(dirname "$conf")" && cp "$BASECONF" "$conf"
    for kv in "$@"; do
      key=${kv%%=*}; val=${kv#*=}
      sed -i "/^PointNPR%3A%3A${key}=/ s/ value=\\\\\"[^\\\\]*\\\\\"/ value=\\\\\"${val}\\\\\"/" "$conf"
      grep -q "^PointNPR%3A%3A${key}=.* value=\\\\\"${val}\\\\\"" "$conf" ||
        { fail "'$name': cannot set PointNPR::$key = $val in $conf"; return 1; }
    done
  fi
  (cd "$T" && exec env HOME="$T/home-$name" XDG_RUNTIME_DIR="$T/home-$name" PNPR_MESHLAB_DECORATE_AT_START=1 \
    PNPR_MESHLAB_SNAPSHOT="$T/$name" "${extra[@]}" ${GUI_ENV[@]+"${GUI_ENV[@]}"} \
    LD_LIBRARY_PATH="$MLLIB${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" timeout 150 "$T/host/meshlab" "$input" \
    ${GUI_INPUTS[@]+"${GUI_INPUTS[@]}"}) \
    > "$T/$name.log" 2>&1 &
  pid=$!
  for i in $(seq 1 1200); do
    [[ -f "$T/$name-camera.txt" && ( -z "${GUI_WAIT:-}" || -f "${GUI_WAIT:-}" ) ]] && break
    kill -0 "$pid" 2> /dev/null || break
    sleep 0.1
  done
  sleep 0.5 # a few more frames after the snapshot (a crash there fails too)
  if kill -0 "$pid" 2> /dev/null; then
    kill "$pid"; wait "$pid" 2> /dev/null
  else
    wait "$pid"; fail "'$name': MeshLab exited by itself (status $?) before it was stopped"
  fi
  if grep -qE "Segmentation fault|Aborted|core dumped|terminate called|Assertion .* failed" "$T/$name.log"; then
    fail "'$name': MeshLab crashed:"; tail -n 20 "$T/$name.log"
  fi
  no_plugin_errors "$name"
  expect_log "$name" "Enabled Decorate mode NPR render"
  expect_log "$name" "NPR render: renderer created \\(OpenGL"
  expect_log "$name" "pointnpr decorator: uploaded ${GUI_POINTS:-15002} points from ${GUI_LAYERS:-1} layer"
  expect_log "$name" "pointnpr decorator: snapshot .* written"
  grep "pointnpr decorator:" "$T/$name.log"
  [[ -f "$T/$name-camera.txt" && -f "$T/$name-npr.pgm" && -f "$T/$name-plain.pgm" ]] || { fail "'$name': no snapshot"; return 1; }
  grep -q "^style $style\$" "$T/$name-camera.txt" || { fail "'$name': style in $name-camera.txt is not $style"; return 1; }
  return 0
}

# aerial_ply OUT: a rolling field [0,100]^2 of 600 x 600 jittered points (z = 0.6 sin(x/7) cos(y/9)
# plus 0.03 noise, greens and browns with noise) and 50 trees (hemispheres of radius 2..4 at
# random places, 2 000 points each, dark green) and a 250 m mast of 200 points at its centre (in
# MeshLab's view, fitted to the bounding box, the field is then small: about 20 points per pixel):
# 460 200 points, coloured, ascii
aerial_ply() {
  awk 'function rnd() { S = (S * 16807) % 2147483647; return S / 2147483647 }
    function c(v) { v = int(v + rnd() * 41 - 20); return v < 0 ? 0 : (v > 255 ? 255 : v) }
    BEGIN { S = 7; n = 600; nt = 50; m = 2000
      printf "ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n", n * n + nt * m + 200
      for (i = 0; i < n; i++) for (j = 0; j < n; j++) {
        x = (i + rnd() - 0.5) * 100 / n; y = (j + rnd() - 0.5) * 100 / n
        z = 0.6 * sin(x / 7) * cos(y / 9) + 0.03 * (rnd() - 0.5)
        g = (int(x / 25) + int(y / 25)) % 2
        printf "%.4f %.4f %.4f %d %d %d\n", x, y, z, c(g ? 120 : 150), c(g ? 150 : 130), c(g ? 70 : 80) }
      for (t = 0; t < nt; t++) {
        cx = 5 + rnd() * 90; cy = 5 + rnd() * 90; r = 2 + 2 * rnd()
        for (k = 0; k < m; k++) {
          u = rnd(); ph = 6.2831853 * rnd(); ct = u; st = sqrt(1 - u * u)
          printf "%.4f %.4f %.4f %d %d %d\n", cx + r * st * cos(ph), cy + r * st * sin(ph), 0.6 * sin(cx / 7) * cos(cy / 9) + r * ct, c(40), c(90), c(40) } }
      for (k = 0; k < 200; k++) printf "50 50 %.4f 90 90 90\n", 1.25 * k }' > "$1"
}

# aerial_ink CAMERA NPR: the fraction of dark pixels (grey < 128) among the samples of the field's
# square [5,95]^2 at z = 0 projected with MeshLab's matrices (steps of 0.5)
aerial_ink() {
  awk 'FILENAME == ARGV[1] { if ($1 == "modelview") for (i = 0; i < 16; i++) M[i] = $(i + 2)
                              if ($1 == "projection") for (i = 0; i < 16; i++) P[i] = $(i + 2)
                              if ($1 == "viewport") { vw = $4; vh = $5 }
                              next }
    FNR == 1 { row = -3 } { row++ }
    row == -1 { W = $1; next }
    row < 1 { next }
    { for (c = 1; c <= NF; c++) px[(row - 1) * W + c - 1] = $c }
    END {
      n = 0; d = 0
      for (x = 5; x <= 95; x += 0.5) for (y = 5; y <= 95; y += 0.5) {
        for (i = 0; i < 4; i++) e[i] = M[i] * x + M[4 + i] * y + M[12 + i]
        for (i = 0; i < 4; i++) cl[i] = P[i] * e[0] + P[4 + i] * e[1] + P[8 + i] * e[2] + P[12 + i] * e[3]
        if (cl[3] <= 0) continue
        X = int((cl[0] / cl[3] + 1) / 2 * vw); Y = int(vh - 1 - (cl[1] / cl[3] + 1) / 2 * vh)
        if (X < 0 || X >= vw || Y < 0 || Y >= vh) continue
        n++; d += px[Y * W + X] < 128 }
      if (n < 1000) exit 1
      printf "%.4f\n", d / n }' "$1" "$2"
}

# check_infobox PREFIX: MeshLab's info box (a band of its log-area colour at alpha 128/255 over the
# bottom rows, drawn by QPainter after the decorations) over our frame is the same overlay as over
# MeshLab's own frame, i.e. the GL state we leave does not change it. From the test hook's frames:
# under-plain P and host-plain F0 (a frame left undrawn: the viewport before and after MeshLab's
# overlay), under-npr N and host-npr F1 (drawn). The band: rows in the lower 40% where F0 differs
# from P in half the pixels. There, where N and P differ by >= 40 grey levels, F1 must be
# F0 + (1 - 128/255) (N - P) within 4 levels for >= 85% of the pixels (measured 90.8%: the rest is
# the text, drawn at another alpha, whose frame rate changes between the frames; a box drawn
# opaque, the bug this guards against, matches almost nowhere).
check_infobox() {
  awk '
    FNR == 1 { f++; row = -3 } { row++ }
    row == -1 { w[f] = $1; h[f] = $2; W = $1; H = $2; next }
    row < 1 { next }
    { for (c = 1; c <= NF; c++) v[f, (row - 1) * W + c - 1] = $c }
    END {
      for (k = 2; k <= 4; k++) if (w[k] != w[1] || h[k] != h[1]) { printf "infobox: frame sizes differ (%dx%d, %dx%d)\n", w[1], h[1], w[k], h[k]; exit 1 }
      a = 128 / 255; band = 0; n = 0; ok = 0
      for (y = int(H * 0.6); y < H; y++) {
        d = 0
        for (x = 0; x < W; x++) { i = y * W + x; e = v[2, i] - v[1, i]; if (e > 3 || e < -3) d++ }
        if (d < W / 2) continue
        band++
        for (x = 0; x < W; x++) {
          i = y * W + x; dp = v[3, i] - v[1, i]
          if (dp < 40 && dp > -40) continue
          n++; e = v[4, i] - (v[2, i] + (1 - a) * dp)
          if (e <= 4 && e >= -4) ok++
        }
      }
      printf "infobox: %d band rows of %dx%d; %d pixels whose frames under the box differ by >= 40: %d (%.1f%%) as predicted from the undrawn frame\n", band, W, H, n, ok, n ? 100 * ok / n : 0
      exit band >= 20 && n >= 2000 && ok >= 0.85 * n ? 0 : 1
    }' "$1-under-plain.pgm" "$1-host-plain.pgm" "$1-under-npr.pgm" "$1-host-npr.pgm"
}

# check_snapshot CAMERA PLAIN NPR NAME: the cube's 4 front edges (z = 1) projected with MeshLab's
# own matrices: on each edge with >= 20 samples in the viewport, >= 80% of the samples have a
# dark pixel (< 110) within 3 px of the edge moved 0..h into the face; >= 2 edges checked. The 4 back edges (z = 0, hidden behind the
# front face in MeshLab's default view): <= 10% dark samples. Front face inside [0.3,0.7]^2:
# <= 5% dark. Background (top-left pixel) exactly paper white in the NPR frame, not in the
# plain one; >= 25% of the pixels differ by more than 40 grey levels from the plain frame.
check_snapshot() {
  awk -v name="$4" '
    FILENAME == ARGV[1] { if ($1 == "modelview") for (i = 0; i < 16; i++) M[i] = $(i + 2)
                          if ($1 == "projection") for (i = 0; i < 16; i++) P[i] = $(i + 2)
                          if ($1 == "viewport") { vx = $2; vy = $3; vw = $4; vh = $5 }
                          next }
    FNR == 1 { f++; row = -3 }
    { row++ }
    row == -1 { W = $1; H = $2; next }
    row < 1 { next }
    { for (c = 1; c <= NF; c++) { if (f == 1) pl[(row - 1) * W + c - 1] = $c; else np[(row - 1) * W + c - 1] = $c } }
    function project(x, y, z,   e, i, cl) {
      for (i = 0; i < 4; i++) e[i] = M[i] * x + M[4 + i] * y + M[8 + i] * z + M[12 + i]
      for (i = 0; i < 4; i++) cl[i] = P[i] * e[0] + P[4 + i] * e[1] + P[8 + i] * e[2] + P[12 + i] * e[3]
      if (cl[3] <= 0) return 0
      PX = (cl[0] / cl[3] + 1) / 2 * vw; PY = vh - 1 - (cl[1] / cl[3] + 1) / 2 * vh
      return PX >= 4 && PX < vw - 4 && PY >= 4 && PY < vh - 4
    }
    function darkNear(px, py, r,   dx, dy, v) {
      for (dy = -r; dy <= r; dy++) for (dx = -r; dx <= r; dx++) { v = np[(int(py + 0.5) + dy) * W + int(px + 0.5) + dx]; if (v < 110) return 1 }
      return 0
    }
    # edge k of the face z: 0 bottom (y=0), 1 top (y=1), 2 left (x=0), 3 right (x=1)
    function edge(k, z, t) { if (k < 2) { EX = t; EY = k } else { EX = k - 2; EY = t } EZ = z }
    END {
      if (W != vw || H != vh) { printf "%s: image %dx%d, viewport %dx%d\n", name, W, H, vw, vh; exit 1 }
      bad = 0; checked = 0
      for (k = 0; k < 4; k++) {
        n = 0; d = 0; nb = 0; db = 0
        for (t = 0.1; t <= 0.9; t += 0.01) {
          # profile lines run through the edge points up to ~0.7h inside the face (docs/lines.md):
          # a dark pixel within 3 px of the edge moved 0..h (h = 0.02) into the front face
          edge(k, 1, t); if (project(EX, EY, EZ)) { n++; hit = 0
            for (s = 0; s <= 0.0201 && !hit; s += 0.004) {
              ix = (k == 2) ? s : (k == 3) ? -s : 0; iy = (k == 0) ? s : (k == 1) ? -s : 0
              if (project(EX + ix, EY + iy, EZ)) hit = darkNear(PX, PY, 3) }
            d += hit }
          edge(k, 0, t); if (project(EX, EY, EZ)) { nb++; db += darkNear(PX, PY, 1) }
        }
        printf "%s: front edge %d: %d of %d samples dark; back edge %d: %d of %d\n", name, k, d, n, k, db, nb
        if (n >= 20) { checked++; if (d < 0.8 * n) bad++ }
        if (nb > 0 && db > 0.1 * nb) bad++
      }
      if (checked < 2) { printf "%s: only %d front edges inside the viewport\n", name, checked; bad++ }
      ni = 0; di = 0
      for (x = 0.3; x <= 0.7; x += 0.02) for (y = 0.3; y <= 0.7; y += 0.02)
        if (project(x, y, 1)) { ni++; if (np[int(PY + 0.5) * W + int(PX + 0.5)] < 110) di++ }
      differ = 0
      for (i = 0; i < W * H; i++) { dv = np[i] - pl[i]; if (dv > 40 || dv < -40) differ++ }
      printf "%s: front face inside: %d of %d samples dark; background npr %d plain %d; %.1f%% of the pixels differ from the plain frame\n", name, di, ni, np[0], pl[0], 100 * differ / (W * H)
      if (ni < 20 || di > 0.05 * ni) bad++
      if (np[0] != 255 || pl[0] == 255) bad++
      if (differ < 0.25 * W * H) bad++
      exit bad ? 1 : 0
    }' "$1" "$2" "$3"
}

# colour_cube_ply OUT: the cube [0,1]^3 grid of cube_ply (50 steps, 15 002 points) with colours:
# the front face (z = 1) yellow (240,200,120) for x < 0.5 and light blue (110,150,230) for
# x >= 0.5, the other faces grey-green (150,190,150); every channel plus uniform integer noise in
# [-30,30] (Park-Miller generator, seed 1: the same file with any awk).
colour_cube_ply() {
  awk -v n=50 'function rnd() { S = (S * 16807) % 2147483647; return S / 2147483647 }
    function ch(v,   c) { c = v + int(rnd() * 61) - 30; return c < 0 ? 0 : (c > 255 ? 255 : c) }
    BEGIN { S = 1
    c = (n + 1) ^ 3 - (n - 1) ^ 3
    printf "ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n", c
    for (i = 0; i <= n; i++) for (j = 0; j <= n; j++) for (k = 0; k <= n; k++) {
      if (i > 0 && i < n && j > 0 && j < n && k > 0 && k < n) continue
      if (k == n && 2 * i < n) { r = 240; g = 200; b = 120 } else if (k == n) { r = 110; g = 150; b = 230 } else { r = 150; g = 190; b = 150 }
      printf "%.10g %.10g %.10g %d %d %d\n", i / n, j / n, k / n, ch(r), ch(g), ch(b)
    } }' > "$1"
}

# colour_stats PLY: mean and standard deviation of the grey level (the decorator'"'"'s PGM formula)
# of the front-face points inside the yellow (x in [0.1,0.4]) and blue (x in [0.6,0.9]) halves,
# y in [0.3,0.7]: "meanY sdY meanB sdB"
colour_stats() {
  awk '/^end_header/ { b = 1; next } b && $3 == 1 && $2 >= 0.3 && $2 <= 0.7 {
      g = int((299 * $4 + 587 * $5 + 114 * $6 + 500) / 1000)
      if ($1 >= 0.1 && $1 <= 0.4) { n[0]++; s[0] += g; q[0] += g * g }
      if ($1 >= 0.6 && $1 <= 0.9) { n[1]++; s[1] += g; q[1] += g * g } }
    END { for (h = 0; h < 2; h++) { m = s[h] / n[h]; printf "%.2f %.2f ", m, sqrt(q[h] / n[h] - m * m) } print "" }' "$1"
}

# measure_colour CAMERA PLAIN NPR NAME [OX]: figures of a frame of the coloured cube (moved by OX
# along x, default 0) in MeshLab's
# default view (front face z = 1 towards the eye; its top and bottom edges are the silhouette
# inside the viewport), projected with MeshLab's own matrices. Prints a readable line on stderr
# and shell assignments on stdout:
#   EDGE  fraction of samples (t = 0.1..0.9 along the front edges inside the viewport) with a dark
#         pixel (< 110) in the image column from one grid spacing h inside the face to 2.5 h
#         outside it (the drawn surface overhangs the true edge by about one disk radius = h)
#   BAND  dark pixels in those columns (the outline ink)
#   MY SY / MB SB  grey mean and standard deviation inside the yellow / blue half (x in
#         [0.1,0.4] / [0.6,0.9], y in [0.3,0.7], steps of 0.01)
#   SEAM  fraction of samples along the colour boundary x = 0.5 (y in [0.2,0.8]) with a dark pixel
#         within 2 px;  DARKIN  fraction of dark pixels among the two halves' samples
#   DIFFER fraction of pixels differing by > 40 grey levels from MeshLab's frame; BG top-left pixel
measure_colour() {
  awk -v name="$4" -v OX="${5:-0}" '
    FILENAME == ARGV[1] { if ($1 == "modelview") for (i = 0; i < 16; i++) M[i] = $(i + 2)
                          if ($1 == "projection") for (i = 0; i < 16; i++) P[i] = $(i + 2)
                          if ($1 == "viewport") { vw = $4; vh = $5 }
                          next }
    FNR == 1 { f++; row = -3 }
    { row++ }
    row == -1 { W = $1; H = $2; next }
    row < 1 { next }
    { for (c = 1; c <= NF; c++) { if (f == 1) pl[(row - 1) * W + c - 1] = $c; else np[(row - 1) * W + c - 1] = $c } }
    function project(x, y, z,   e, i, cl) {
      for (i = 0; i < 4; i++) e[i] = M[i] * (x + OX) + M[4 + i] * y + M[8 + i] * z + M[12 + i]
      for (i = 0; i < 4; i++) cl[i] = P[i] * e[0] + P[4 + i] * e[1] + P[8 + i] * e[2] + P[12 + i] * e[3]
      if (cl[3] <= 0) return 0
      PX = (cl[0] / cl[3] + 1) / 2 * vw; PY = vh - 1 - (cl[1] / cl[3] + 1) / 2 * vh
      return PX >= 12 && PX < vw - 12 && PY >= 12 && PY < vh - 12
    }
    function px(x, y) { return np[int(y + 0.5) * W + int(x + 0.5)] }
    function darkNear(x, y, r,   dx, dy) {
      for (dy = -r; dy <= r; dy++) for (dx = -r; dx <= r; dx++) if (px(x + dx, y + dy) < 110) return 1
      return 0
    }
    END {
      if (W != vw || H != vh) { printf "%s: image %dx%d, viewport %dx%d\n", name, W, H, vw, vh > "/dev/stderr"; exit 1 }
      n = 0; d = 0; band = 0; hsum = 0
      for (k = 0; k < 2; k++) for (t = 0.1; t <= 0.9001; t += 0.01) {
        if (!project(t, k ? 1 - 0.02 : 0.02, 1)) continue
        iy = PY
        if (!project(t, k, 1)) continue
        n++; ex = PX; ey = PY; hit = 0
        # the column from one spacing inside the face to 2.5 spacings outside it (the drawn
        # surface, disks of about one spacing, overhangs the true edge)
        hp = ey - iy; dir = hp < 0 ? -1 : 1; hp = hp * dir; hsum += hp
        for (o = -hp; o <= 2.5 * hp; o++) if (px(ex, ey + dir * o) < 110) { band++; hit = 1 }
        d += hit
      }
      for (h = 0; h < 2; h++) { cnt[h] = 0; sum[h] = 0; sq[h] = 0 }
      dark = 0
      for (x = 0.1; x <= 0.9001; x += 0.01) {
        if (x > 0.4001 && x < 0.5999) continue
        h = x < 0.5 ? 0 : 1
        for (y = 0.3; y <= 0.7001; y += 0.01) if (project(x, y, 1)) {
          v = px(PX, PY); cnt[h]++; sum[h] += v; sq[h] += v * v; dark += v < 110 }
      }
      ns = 0; ds = 0
      for (y = 0.2; y <= 0.8001; y += 0.01) if (project(0.5, y, 1)) { ns++; ds += darkNear(PX, PY, 2) }
      differ = 0
      for (i = 0; i < W * H; i++) { dv = np[i] - pl[i]; if (dv > 40 || dv < -40) differ++ }
      for (h = 0; h < 2; h++) { m[h] = cnt[h] ? sum[h] / cnt[h] : -1; sd[h] = cnt[h] ? sqrt(sq[h] / cnt[h] - m[h] * m[h]) : -1 }
      printf "%s: silhouette (front top/bottom edges, spacing %.1f px): %d of %d samples dark, %d dark pixels in their bands; yellow half grey %.1f sd %.2f (%d samples), blue half %.1f sd %.2f (%d); colour boundary: %d of %d samples dark; %d of %d inside samples dark; %.1f%% of the pixels differ from MeshLab'"'"'s frame; background %d\n",
             name, n ? hsum / n : 0, d, n, band, m[0], sd[0], cnt[0], m[1], sd[1], cnt[1], ds, ns, dark, cnt[0] + cnt[1], 100 * differ / (W * H), np[0] > "/dev/stderr"
      printf "EDGE=%.4f BAND=%d MY=%.2f SY=%.3f MB=%.2f SB=%.3f SEAM=%.4f DARKIN=%.4f DIFFER=%.4f BG=%d NEDGE=%d NIN=%d\n",
             n ? d / n : 0, band, m[0], sd[0], m[1], sd[1], ns ? ds / ns : 1, (cnt[0] + cnt[1]) ? dark / (cnt[0] + cnt[1]) : 1, differ / (W * H), np[0], n, cnt[0] + cnt[1]
    }' "$1" "$2" "$3"
}

# measure_sides RUN VAR: measure_colour of run RUN's frame for the cube at x 0 (left) and its copy
# at x 1.2 (right), as the shell variables VAR_left_FIGURE and VAR_right_FIGURE
measure_sides() {
  local side out
  for side in left:0 right:1.2; do
    out=$(measure_colour "$T/$1-camera.txt" "$T/$1-plain.pgm" "$T/$1-npr.pgm" "$1-${side%%:*}" "${side#*:}") ||
      { fail "'$1': cannot measure the ${side%%:*} cube"; continue; }
    eval "$(sed "s/\([A-Z]*\)=/$2_${side%%:*}_\1=/g" <<< "$out")"
  done
}

# holds NAME "DESCRIPTION" AWK-CONDITION: fails NAME when the condition on the figures is false
holds() { awk "BEGIN { exit ($3) ? 0 : 1 }" || fail "'$1': $2 (figures: $3)"; }

setup_host
start_xvfb
log "meshlabserver from $T/host on display $DISPLAY"

case "$TEST" in
load)
  # The plugin loads (no loader error naming it) and registers both filters with every parameter.
  mlserver dump -d "$T/filters.html" || true
  expect_rc dump 0
  no_plugin_errors dump
  [[ -f "$T/filters.html" ]] || die "meshlabserver -d wrote no filter list"
  for f in "NPR: Compute feature degree and classify points" "NPR: Select feature points" "NPR: Profile lines" \
           "NPR: Segment (JSEG)" "NPR: Segment (connected components / colour region growing)" \
           "NPR: Set layer style" "NPR: Open a sample of a large PLY"; do
    grep -qF "$f" "$T/filters.html" || fail "filter '$f' is not registered"
  done
  # the list shows each parameter's type and description
  for p in "Int:Neighbours (k)" "Float:Feature threshold" "Float:Geometry weight" "Float:Colour weight" \
           "Float:Directional confidence" "Float:Dither scale" "Bool:Recompute normals" \
           "Bool:Orient towards viewpoint" "Point3f:Viewpoint" "Bool:Colour points by class" "Enum:Class" \
           "Bool:Add to current selection" "Float:Sample spacing h" "Float:Neighbourhood radius" \
           "Float:Merge tolerance" "Float:Minimum line length" "Float:Direction weight" "Int:Noise-reducing shifts" \
           "Bool:Join at corners" "Bool:Recompute features" "Int:Segment count (hierarchy)" "Float:Hierarchy threshold" \
           "Int:Colour classes" "Float:Class merge distance" "Float:Seed factor" "Float:Region merge distance" \
           "Int:Minimum segment size" "Bool:Colour vertices by segment" "Bool:Label to vertex quality" "Enum:Method" \
           "Float:Neighbour distance" "Float:Point colour distance" "Enum:Style" "FileName:PLY file" "Int:Points"; do
    grep -qF "\c ${p%%:*}  </TD> <TD> ${p#*:} </TD>" "$T/filters.html" || fail "parameter '$p' missing from the filter list"
  done
  # the same plugin loaded into the interactive host's plugin folder layout works with a script too
  cube_ply "$T/cube.ply" 1 10 0 0 0
  mlx "$T/f.mlx" "$(features_xml)"
  mlserver run -i "$T/cube.ply" -o "$T/out.ply" -m vq -s "$T/f.mlx" && expect_rc run 0
  no_plugin_errors run
  expect_log run "pointnpr: layer"
  # NPR: Set layer style: the library's styles by name (index + 1), 0 = the decoration's Style
  style_xml() {
    printf ' <filter name="NPR: Set layer style">\n  <Param type="RichEnum" name="style" value="%s" enum_cardinality="9"/>\n </filter>\n' "$1"
  }
  mlx "$T/style.mlx" "$(style_xml 5)" "$(style_xml 0)"
  mlserver style -i "$T/cube.ply" -o "$T/style-out.ply" -s "$T/style.mlx" && expect_rc style 0
  expect_log style "pointnpr: layer 'cube.ply' is drawn in the cartoon style by the NPR render decoration"
  expect_log style "pointnpr: layer 'cube.ply' takes the NPR render decoration's Style"
  ;;

cube | offset)
  # (a) generated cube with known answers: edges high quality + directional, faces ~0.
  if [[ "$TEST" == cube ]]; then side=1; ox=0; oy=0; oz=0; else side=1000; ox=10000000; oy=-10000000; oz=5000000; fi
  n=50; h=$(awk -v s=$side -v n=$n 'BEGIN { printf "%.10g", s / n }')
  cube_ply "$T/cube.ply" $side $n $ox $oy $oz
  mlx "$T/f.mlx" "$(features_xml color=true)" "$(select_xml 0)"
  if mlserver run -i "$T/cube.ply" -o "$T/out.ply" -m vq vc vn vf -s "$T/f.mlx"; then
    expect_rc run 0
    expect_log run "15002 points \\(15002 valid\\), k 16, threshold [0-9.]+ \\(automatic\\), without colour, normals computed"
    expect_log run "selected [0-9]+ directional feature points"
    expect_no_log run "pointnpr: WARNING" # h = 20 at 1e7 is 20 float steps: nothing lost
    to_ascii "$T/out.ply" "$T/out-ascii.ply" &&
      { check_cube "$T/out-ascii.ply" $side "$h" $ox $oy $oz || fail "cube known answers (see the line above)"; }
    grep -E "feature points|; [0-9.]+ s" "$T/run.log" | head -3
  fi
  # viewpoint at the cube's centre (scene coordinates): every computed normal must point inwards
  c=$(awk -v s=$side -v x=$ox -v y=$oy -v z=$oz 'BEGIN { printf "vx=%.10g vy=%.10g vz=%.10g", x + s / 2, y + s / 2, z + s / 2 }')
  # shellcheck disable=SC2086
  mlx "$T/vp.mlx" "$(features_xml usevp=true $c)"
  if mlserver vp -i "$T/cube.ply" -o "$T/vp.ply" -m vn -s "$T/vp.mlx" && expect_rc vp 0 && to_ascii "$T/vp.ply" "$T/vp-a.ply"; then
    awk -v s=$side -v ox=$ox -v oy=$oy -v oz=$oz '/^property/ && !b { col[$NF] = np++ } /^end_header/ { b = 1; next }
      b { dx = $(col["x"] + 1) - ox - s / 2; dy = $(col["y"] + 1) - oy - s / 2; dz = $(col["z"] + 1) - oz - s / 2
          dot = dx * $(col["nx"] + 1) + dy * $(col["ny"] + 1) + dz * $(col["nz"] + 1); n++; if (dot >= 0) out++ }
      END { printf "viewpoint at the centre: %d of %d normals point outwards\n", out, n; exit n > 0 && out == 0 ? 0 : 1 }' \
      "$T/vp-a.ply" || fail "normals not oriented towards the viewpoint"
  fi
  [[ "$TEST" == offset ]] && float_offset_cube
  ;;

select)
  # Each class choice selects exactly the vertices of that class (class read back from the
  # palette colours), "add to selection" keeps the earlier selection.
  cube_ply "$T/cube.ply" 1 40 0 0 0
  for c in 0 1 2 3; do
    mlx "$T/s$c.mlx" "$(features_xml color=true dither=3)" "$(select_xml $c)"
    mlserver sel$c -i "$T/cube.ply" -o "$T/sel$c.ply" -m vc vf -s "$T/s$c.mlx" || continue
    expect_rc sel$c 0
    to_ascii "$T/sel$c.ply" "$T/sel$c-a.ply" || continue
    awk -v want=$c '
      /^property/ && !b { col[$NF] = np++ } /^end_header/ { b = 1; next }
      b { r = $(col["red"] + 1); g = $(col["green"] + 1); s = int($(col["flags"] + 1) / 32) % 2
          k = r == 220 ? 2 : (r == 40 ? 1 : (r == 20 ? 3 : 0))
          w = want == 0 ? k == 2 : (want == 1 ? k == 1 : (want == 2 ? (k == 1 || k == 2) : k == 3))
          n++; sel += s; if (s != w) bad++; if (w) expect++ }
      END { printf "class choice %d: %d of %d selected, expected %d, mismatches %d\n", want, sel, n, expect, bad
            exit (bad == 0 && (expect > 0 || want == 1)) ? 0 : 1 }' "$T/sel$c-a.ply" ||
      fail "selection of class choice $c does not match the classes"
  done
  # attributes of an older version of the layer (MeshLab keeps attribute handles when a filter
  # moves the vertices, and through File > Reload): refused with the reason, not used
  translate_xml='<filter name="Transform: Translate, Center, set Origin"><Param type="RichEnum" name="traslMethod" value="0" enum_cardinality="3"/><Param type="RichDynamicFloat" name="axisX" value="0.25" min="-10" max="10"/><Param type="RichDynamicFloat" name="axisY" value="0" min="-10" max="10"/><Param type="RichDynamicFloat" name="axisZ" value="0" min="-10" max="10"/><Param type="RichPoint3f" name="newOrigin" x="0" y="0" z="0"/><Param type="RichBool" name="Freeze" value="true"/><Param type="RichBool" name="allLayers" value="false"/></filter>'
  mlx "$T/stale.mlx" "$(features_xml)" "$translate_xml" "$(select_xml 0)"
  mlserver stale -i "$T/cube.ply" -o "$T/stale.ply" -s "$T/stale.mlx"
  expect_log stale "pointnpr: layer 'cube.ply': its feature classes belong to an older version of the layer"
  expect_no_log stale "pointnpr: layer 'cube.ply': selected"
  # ... and computing the features again drops the old ones and stamps the new: the selection runs
  mlx "$T/fresh.mlx" "$(features_xml)" "$translate_xml" "$(features_xml)" "$(select_xml 0)"
  mlserver fresh -i "$T/cube.ply" -o "$T/fresh.ply" -s "$T/fresh.mlx" && expect_rc fresh 0
  expect_log fresh "pointnpr: layer 'cube.ply': dropped the attributes of an older version of the layer"
  expect_no_log fresh "its feature classes belong to an older version"
  mlx "$T/add.mlx" "$(features_xml color=true dither=3)" "$(select_xml 0)" "$(select_xml 3 true)"
  if mlserver add -i "$T/cube.ply" -o "$T/add.ply" -m vc vf -s "$T/add.mlx" && to_ascii "$T/add.ply" "$T/add-a.ply"; then
    awk '/^property/ && !b { col[$NF] = np++ } /^end_header/ { b = 1; next }
      b { r = $(col["red"] + 1); s = int($(col["flags"] + 1) / 32) % 2; w = (r == 220 || r == 20); if (s != w) bad++; sel += s }
      END { printf "directional + dithering: %d selected, mismatches %d\n", sel, bad; exit bad == 0 && sel > 0 ? 0 : 1 }' \
      "$T/add-a.ply" || fail "add to selection"
  fi
  ;;

sample)
  # NPR: Open a sample of a large PLY: a 40 000-point roof (a ridge at x = 1) with the features of pointnpr, as
  # written and ordered for drawing: about the asked 5 000 points in a new layer (saved as the
  # current one), on the roof, the file's features as vertex quality (the ridge's points alone
  # above 0.05); a missing file and a bad count refused, no layer added.
  awk 'BEGIN { n = 200; print "ply\nformat ascii 1.0\nelement vertex " n * n
    print "property float x\nproperty float y\nproperty float z\nend_header"
    for (j = 0; j < n; j++) for (i = 0; i < n; i++) printf "%g %g %g\n", i * 0.01, j * 0.01, 0.5 * (i > 100 ? i - 100 : 100 - i) * 0.01 }' > "$T/plane.txt.ply"
  "$CLI" features "$T/plane.txt.ply" -o "$T/plane.ply" --quiet || die "pointnpr features failed"
  "$CLI" convert "$T/plane.ply" -o "$T/plane_lod.ply" --lod --quiet || die "pointnpr convert --lod failed"
  cube_ply "$T/cube.ply" 1 10 0 0 0 # the layer MeshLab opens with
  open_xml() { printf ' <filter name="NPR: Open a sample of a large PLY">\n  <Param type="RichOpenFile" name="file" value="%s" exts_cardinality="1" exts_val0="*.ply"/>\n  <Param type="RichInt" name="points" value="%s"/>\n </filter>\n' "$1" "$2"; }
  for f in plane plane_lod; do
    mlx "$T/$f.mlx" "$(open_xml "$T/$f.ply" 5000)"
    mlserver "$f" -i "$T/cube.ply" -o "$T/${f}_s.ply" -m vq vn -s "$T/$f.mlx" || continue
    expect_rc "$f" 0
    expect_log "$f" "new layer '$f.ply sample': [0-9]+ of the 40000 points"
    expect_log "$f" "the file's features kept"
    to_ascii "$T/${f}_s.ply" "$T/${f}_a.ply" || continue
    awk '/^property/ && !b { col[$NF] = np++ } /^end_header/ { b = 1; next }
      b { n++; q = $(col["quality"] + 1); if (q > 0.05) { edge++; if ($1 < 0.9 || $1 > 1.1) off++ } if ($1 < 0 || $1 > 2 || $2 < 0 || $2 > 2) out++ }
      END { printf "sample: %d points, %d of quality > 0.05 (%d off the ridge), %d outside the roof\n", n, edge, off, out
            exit (n > 4500 && n < 5500 && edge > 20 && edge < n / 4 && off == 0 && out == 0) ? 0 : 1 }' "$T/${f}_a.ply" ||
      fail "'$f': not about 5000 points of the roof with its features (above)"
  done
  # the same roof at (5e5, 4.2e6, 100) in doubles, without features: the layer holds offsets from
  # its transformation, so MeshLab's floats (a step of 0.5 at 4.2e6) keep the 0.01 spacing, and the
  # features filter on the layer finds the ridge (on world floats it would find nothing: see
  # meshlab_offset)
  awk 'BEGIN { n = 200; print "ply\nformat ascii 1.0\nelement vertex " n * n
    print "property double x\nproperty double y\nproperty double z\nend_header"
    for (j = 0; j < n; j++) for (i = 0; i < n; i++)
      printf "%.2f %.2f %.3f\n", 500000 + i * 0.01, 4200000 + j * 0.01, 100 + 0.5 * (i > 100 ? i - 100 : 100 - i) * 0.01 }' > "$T/geo.txt.ply"
  "$CLI" convert "$T/geo.txt.ply" -o "$T/geo_bin.ply" --quiet && "$CLI" convert "$T/geo_bin.ply" -o "$T/geo.ply" --lod --quiet ||
    die "pointnpr convert --lod failed"
  mlx "$T/geo.mlx" "$(open_xml "$T/geo.ply" 5000)" "$(features_xml)"
  if mlserver geo -i "$T/cube.ply" -o "$T/geo_s.ply" -m vq -s "$T/geo.mlx" && expect_rc geo 0 &&
    to_ascii "$T/geo_s.ply" "$T/geo_a.ply"; then
    expect_log geo "its positions are offsets from 500001\.000 4200001\.000 100\.[0-9]*, the layer's transformation"
    awk '/^property/ && !b { col[$NF] = np++ } /^end_header/ { b = 1; next }
      b { n++; k = $1 " " $2; if (!(k in seen)) { seen[k] = 1; d++ } q = $(col["quality"] + 1)
          if (q > 0.05) { edge++; if ($1 < -0.1 || $1 > 0.1) off++ } }
      END { printf "georeferenced sample: %d points on %d distinct x y, %d of quality > 0.05 (%d off the ridge)\n", n, d, edge, off
            exit (n > 4500 && d == n && edge > 20 && off == 0) ? 0 : 1 }' "$T/geo_a.ply" ||
      fail "the georeferenced sample lost its precision or its ridge (above)"
  fi
  # an edited sample (a filter moved its points) is no longer the file's: computing its features
  # drops the file it samples, so that the decoration draws it as edited
  mlx "$T/edited.mlx" "$(open_xml "$T/plane_lod.ply" 5000)" '<filter name="Transform: Translate, Center, set Origin"><Param type="RichEnum" name="traslMethod" value="0" enum_cardinality="3"/><Param type="RichDynamicFloat" name="axisX" value="0.25" min="-10" max="10"/><Param type="RichDynamicFloat" name="axisY" value="0" min="-10" max="10"/><Param type="RichDynamicFloat" name="axisZ" value="0" min="-10" max="10"/><Param type="RichPoint3f" name="newOrigin" x="0" y="0" z="0"/><Param type="RichBool" name="Freeze" value="true"/><Param type="RichBool" name="allLayers" value="false"/></filter>' "$(features_xml)"
  mlserver edited -i "$T/cube.ply" -o "$T/edited_s.ply" -s "$T/edited.mlx" && expect_rc edited 0 &&
    expect_log edited "dropped the attributes of an older version of the layer \\(reloaded or edited\\); as edited it is no longer a sample of its file"
  # MeshLab's own importer opens the ordered file whole (the index element skipped)
  if mlserver import -i "$T/plane_lod.ply" -o "$T/import.ply" && expect_rc import 0 && to_ascii "$T/import.ply" "$T/import_a.ply"; then
    grep -q '^element vertex 40000$' "$T/import_a.ply" || fail "MeshLab did not open the 40000 points of the ordered file"
  fi
  expect_log plane "a pass over every point first"
  expect_log plane_lod "ordered for drawing: only the runs of the sample were read"
  mlx "$T/none.mlx" "$(open_xml "$T/none.ply" 5000)"
  mlserver none -i "$T/cube.ply" -o "$T/none_s.ply" -s "$T/none.mlx" && expect_rc none 255 && expect_log none "none.ply.*no layer was added"
  mlx "$T/zero.mlx" "$(open_xml "$T/plane_lod.ply" 0)"
  mlserver zero -i "$T/cube.ply" -o "$T/zero_s.ply" -s "$T/zero.mlx" && expect_rc zero 255 && expect_log zero "the points must be > 0"
  ;;

robust)
  # (c) never a crash; clear messages.
  printf 'ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n' > "$T/empty.ply"
  mlx "$T/f.mlx" "$(features_xml)"
  mlserver empty -i "$T/empty.ply" -o "$T/empty-out.ply" -s "$T/f.mlx" && expect_rc empty 255 &&
    expect_log empty "has no vertices: nothing to analyse"

  # a mesh with faces: a 30x30 grid with a ridge, triangulated
  awk 'BEGIN { n = 30; printf "ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n", n * n, 2 * (n - 1) * (n - 1)
    for (j = 0; j < n; j++) for (i = 0; i < n; i++) { x = i / (n - 1); printf "%g %g %g\n", x, j / (n - 1), (x < 0.5 ? x : 1 - x) * 0.5 }
    for (j = 0; j < n - 1; j++) for (i = 0; i < n - 1; i++) { a = j * n + i; printf "3 %d %d %d\n3 %d %d %d\n", a, a + 1, a + n + 1, a, a + n + 1, a + n } }' > "$T/mesh.ply"
  if mlserver mesh -i "$T/mesh.ply" -o "$T/mesh-out.ply" -m vq -s "$T/f.mlx"; then
    expect_rc mesh 0
    expect_log mesh "is a mesh with 1682 faces: the features use its 900 vertices only"
    expect_log mesh "normals kept from the layer"
  fi

  # a coloured plane, left half red, right half blue, no normals: the colour term finds the
  # boundary (quality high within one spacing of x = 0.5, ~0 three spacings away)
  awk 'BEGIN { n = 60; printf "ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n", n * n
    for (j = 0; j < n; j++) for (i = 0; i < n; i++) { x = (i + 0.5) / n; printf "%g %g 0 %s\n", x, (j + 0.5) / n, x < 0.5 ? "255 0 0" : "0 0 255" } }' > "$T/colour.ply"
  mlx "$T/c.mlx" "$(features_xml)"
  if mlserver colour -i "$T/colour.ply" -o "$T/colour-out.ply" -m vq vc -s "$T/c.mlx"; then
    expect_rc colour 0
    expect_log colour "with colour, normals computed"
    to_ascii "$T/colour-out.ply" "$T/colour-a.ply" &&
    awk '/^property/ && !b { col[$NF] = np++ } /^end_header/ { b = 1; next }
      b { x = $(col["x"] + 1); q = $(col["quality"] + 1); r = $(col["red"] + 1); d = x - 0.5; if (d < 0) d = -d
          if (d < 1 / 60) { nb++; qb += q } else if (d > 3 / 60) { nf++; if (q > qf) qf = q }
          if ((x < 0.5) != (r == 255)) recoloured++ }
      END { printf "colour boundary: mean quality %.3f (%d points), elsewhere max %.3f (%d points), recoloured %d\n", qb / nb, nb, qf, nf, recoloured
            exit (qb / nb >= 0.3 && qf < 0.05 && recoloured == 0) ? 0 : 1 }' "$T/colour-a.ply" || fail "colour boundary"
  fi

  # NaN coordinates (MeshLab's loader may drop them; either way no crash and a result)
  { printf 'ply\nformat ascii 1.0\nelement vertex 1002\nproperty float x\nproperty float y\nproperty float z\nend_header\nnan 0 0\n0 nan inf\n'
    awk 'BEGIN { for (i = 0; i < 1000; i++) printf "%g %g 0\n", (i % 40) / 40, int(i / 40) / 40 }'; } > "$T/nan.ply"
  mlserver nan -i "$T/nan.ply" -o "$T/nan-out.ply" -m vq -s "$T/f.mlx" && expect_rc nan 0 &&
    expect_log nan "2 of 1002 vertices have NaN/Inf coordinates: they are left out" &&
    expect_log nan "1002 points \\(1000 valid\\)"

  # a point cloud of 1e7 offsets along every axis with too few points for k: clamped, no crash
  printf 'ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\nend_header\n1e7 1e7 1e7\n10000001 1e7 1e7\n1e7 10000001 1e7\n1e7 1e7 10000001\n10000001 10000001 1e7\n' > "$T/tiny.ply"
  mlserver tiny -i "$T/tiny.ply" -o "$T/tiny-out.ply" -m vq -s "$T/f.mlx" && expect_rc tiny 0 &&
    expect_log tiny "5 points \\(5 valid\\), k 5" &&
    expect_log tiny "WARNING: layer 'tiny.ply' lies up to 10000001 from the origin, .* a median 1 apart \\(1 times the step\\)"

  # bad parameters and selection before features: an error message, MeshLab keeps running
  cube_ply "$T/cube.ply" 1 10 0 0 0
  mlx "$T/bad.mlx" "$(features_xml k=0)"
  mlserver badk -i "$T/cube.ply" -o "$T/badk-out.ply" -s "$T/bad.mlx" && expect_rc badk 255 && expect_log badk "k must be in 1..1024 \\(got 0\\)"
  mlx "$T/bad2.mlx" "$(features_xml wg=0 wc=0)"
  mlserver badw -i "$T/cube.ply" -o "$T/badw-out.ply" -s "$T/bad2.mlx" && expect_rc badw 255 && expect_log badw "weights must be non-negative and not both 0"
  mlx "$T/sel.mlx" "$(select_xml 0)"
  mlserver selfirst -i "$T/cube.ply" -o "$T/selfirst-out.ply" -s "$T/sel.mlx" && expect_rc selfirst 255 &&
    expect_log selfirst "has no feature classes \\(per-vertex attribute feature_class\\): run 'NPR: Compute feature degree and classify points' on it first"
  # meshlabserver stops a script at a failed filter (exit 255, "Problem with filter"); a good run
  # afterwards still works
  mlx "$T/ok.mlx" "$(features_xml)" "$(select_xml 2)"
  mlserver ok -i "$T/cube.ply" -o "$T/ok-out.ply" -s "$T/ok.mlx" && expect_rc ok 0
  for r in empty badk badw selfirst; do
    [[ -f "$T/$r.rc" ]] && log "$r: exit status $(cat "$T/$r.rc"): $(grep 'LOG: .*pointnpr:' "$T/$r.log" | tail -n 1)"
  done
  ;;

lion)
  # (b) the real sample scan (342k coloured points): fetched and converted once, cached in WORKDIR.
  CACHE="$WORK/sample-cache"
  LION="$WORK/lion.ply"
  if [[ ! -s "$LION" ]]; then
    tiles=$(bash "$SRC/scripts/fetch-sample.sh" "$CACHE" | tail -n 1) ||
      die "could not fetch the sample scan (scripts/fetch-sample.sh $CACHE): this test needs it"
    "$CLI" convert "$tiles" -o "$LION" --quiet || die "pointnpr convert of $tiles failed" # written whole or not at all
  fi
  mlx "$T/f.mlx" "$(features_xml)"
  if mlserver lion -i "$LION" -o "$T/lion-out.ply" -m vq vc vn -s "$T/f.mlx"; then
    expect_rc lion 0
    expect_log lion "with colour, normals computed and written back"
    grep -E "pointnpr: (layer|[0-9]+ feature)" "$T/lion.log"
    log "meshlabserver wall time (load + filter + save): $(cat "$T/lion.secs") s"
    # The same analysis through the CLI on the same file. MeshLab holds float coordinates (the file
    # has doubles) and the plugin's origin is the bounding-box centre, so per-point values may
    # differ slightly where kNN ties break differently: degrees must agree within 0.05 at 99.5% of
    # the points and the class counts within 2%.
    "$CLI" features "$LION" -o "$T/lion-cli.ply" --ascii --quiet || fail "pointnpr features failed"
    to_ascii "$T/lion-out.ply" "$T/lion-out-a.ply"
    counts=$(sed -n 's/^pointnpr: \([0-9]*\) feature points (\([0-9]*\) directional, [0-9]* non-directional), \([0-9]*\) dithering points.*/\1 \2 \3/p' "$T/lion.log" | head -n 1)
    [[ -n "$counts" ]] || fail "no class counts in the plugin's log"
    read -r pf pd pdi <<< "${counts:-0 0 0}"
    awk -v pf="$pf" -v pd="$pd" -v pdi="$pdi" 'FNR == 1 { file++; b = 0; np = 0; delete col }
      /^property/ && !b { col[$NF] = np++ } /^end_header/ { b = 1; i = 0; next }
      b && file == 1 { deg[i] = $(col["feature_degree"] + 1); rgb[i] = $(col["red"] + 1) " " $(col["green"] + 1) " " $(col["blue"] + 1)
                       c = $(col["feature_class"] + 1); cf += (c == 1 || c == 2); cd += (c == 2); cdi += (c == 3); i++ }
      b && file == 2 { q = $(col["quality"] + 1); d = q - deg[i]; if (d < 0) d = -d; if (d > 0.05) diff++
                       if (q > 0.15) high++; if (q < 0 || q > 1) out++
                       if ($(col["red"] + 1) " " $(col["green"] + 1) " " $(col["blue"] + 1) != rgb[i]) recol++; i++; n++ }
      function near(a, b) { return a >= 0.98 * b && a <= 1.02 * b }
      END { printf "lion: %d points; quality vs CLI feature_degree: |diff| > 0.05 at %d; quality > 0.15 at %.1f%%, outside [0,1] %d; colours changed %d\n", n, diff, 100 * high / n, out, recol
            printf "lion: plugin / CLI: feature points %d / %d, directional %d / %d, dithering %d / %d\n", pf, cf, pd, cd, pdi, cdi
            exit (n > 300000 && diff <= n / 200 && out == 0 && high > n / 100 && high < n / 2 && recol == 0 &&
                  near(pf, cf) && near(pd, cd) && near(pdi, cdi) && pd > 0 && pdi > 0) ? 0 : 1 }' \
      "$T/lion-cli.ply" "$T/lion-out-a.ply" || fail "lion results"
  fi
  # profile lines of the sample scan as a new polyline layer (OBJ keeps it): as many polylines as
  # the CLI finds on the same file (within 10%), every vertex inside the scan's bounding box
  mlx "$T/ll.mlx" "$(lines_xml)"
  if mlserver lionlines -i "$LION" -o "$T/lion-lines.obj" -s "$T/ll.mlx"; then
    expect_rc lionlines 0
    expect_log lionlines "new layer 'lion.ply profile lines'"
    "$CLI" lines "$LION" -o "$T/lion-lines-cli.obj" --quiet || fail "pointnpr lines failed"
    # MeshLab writes one `l a b` per edge, the CLI one `l` per polyline: compare total lengths
    objlen() { awk '/^v / { n++; x[n] = $2; y[n] = $3; z[n] = $4 }
                    /^l / { for (i = 3; i <= NF; i++) { a = $(i - 1); b = $i; sub(/\/.*/, "", a); sub(/\/.*/, "", b)
                            t += sqrt((x[a] - x[b]) ^ 2 + (y[a] - y[b]) ^ 2 + (z[a] - z[b]) ^ 2) } }
                    END { printf "%.4f", t }' "$1"; }
    pl=$(objlen "$T/lion-lines.obj")
    cl=$(objlen "$T/lion-lines-cli.obj")
    log "lion lines: plugin total length $pl, CLI $cl"
    awk -v p="$pl" -v c="$cl" 'BEGIN { exit (c > 5 && p >= 0.9 * c && p <= 1.1 * c) ? 0 : 1 }' || fail "lion lines: total length $pl vs $cl from the CLI"
    awk '/^v / { if ($2 < -5.1 || $2 > -0.7 || $3 < 0.9 || $3 > 6.9 || $4 < -3.6 || $4 > 1.3) bad++; n++ }
         END { printf "lion lines: %d vertices, %d outside the scan box\n", n, bad; exit (n > 0 && bad == 0) ? 0 : 1 }' \
      "$T/lion-lines.obj" || fail "lion line vertices"
  fi
  # JSEG segment labels of the sample scan (label to quality): as many segments as the CLI finds
  mlx "$T/lj.mlx" "$(jseg_xml)"
  if mlserver lionjseg -i "$LION" -o "$T/lion-jseg.ply" -m vq vc -s "$T/lj.mlx"; then
    expect_rc lionjseg 0
    "$CLI" segment "$LION" -o "$T/lion-jseg-cli.ply" --ascii --quiet || fail "pointnpr segment failed"
    to_ascii "$T/lion-jseg.ply" "$T/lion-jseg-a.ply"
    ps=$(awk '/^property/ && !b { col[$NF] = np++ } /^end_header/ { b = 1; next } b { seen[$(col["quality"] + 1)] = 1 }
              END { for (s in seen) n++; print n + 0 }' "$T/lion-jseg-a.ply")
    cs=$(awk '/^property/ && !b { col[$NF] = np++ } /^end_header/ { b = 1; next } b { seen[$(col["segment"] + 1)] = 1 }
              END { for (s in seen) n++; print n + 0 }' "$T/lion-jseg-cli.ply")
    log "lion JSEG: plugin $ps segments, CLI $cs"
    awk -v p="$ps" -v c="$cs" 'BEGIN { exit (p >= 20 && p >= 0.8 * c && p <= 1.2 * c) ? 0 : 1 }' || fail "lion JSEG: $ps segments vs $cs from the CLI"
  fi
  ;;

lines)
  # Profile lines of the sampled cube [0,1]^3 (the cube test's grid, h = 0.02) as a new polyline
  # layer saved as OBJ: >= 12 polylines, every vertex within 2h of a cube edge, total length within
  # 10% of 12. (a) features computed by the lines filter, (b) from the feature filter's stored
  # attributes, (c) a cube of side 1000 at (1e7, -1e7, 5e6), (d) robustness.
  n=50
  cube_ply "$T/cube.ply" 1 $n 0 0 0
  mlx "$T/l.mlx" "$(lines_xml)"
  if mlserver lines -i "$T/cube.ply" -o "$T/lines.obj" -s "$T/l.mlx"; then
    expect_rc lines 0
    expect_log lines "layer 'cube.ply' analysed for the lines \\(it is left unchanged\\): 15002 points"
    expect_log lines "new layer 'cube.ply profile lines'"
    grep -m1 "directional points ->" "$T/lines.log"
    check_cube_lines "$T/lines.obj" 1 0.02 0 0 0 || fail "cube lines, features computed by the filter (see above)"
  fi
  mlx "$T/fl.mlx" "$(features_xml)" "$(lines_xml)"
  if mlserver stored -i "$T/cube.ply" -o "$T/stored.obj" -s "$T/fl.mlx"; then
    expect_rc stored 0
    expect_log stored "feature classes and directions taken from its attributes"
    check_cube_lines "$T/stored.obj" 1 0.02 0 0 0 || fail "cube lines from stored features (see above)"
  fi
  cube_ply "$T/far.ply" 1000 $n 10000000 -10000000 5000000
  if mlserver far -i "$T/far.ply" -o "$T/far.obj" -s "$T/l.mlx"; then
    expect_rc far 0
    check_cube_lines "$T/far.obj" 1000 20 10000000 -10000000 5000000 || fail "cube lines at 1e7 (see above)"
  fi
  # robustness: empty layer, no directional points (a plane), lines shorter than the minimum
  # length, a bad parameter: exit 255 with the message and nothing saved; NaN vertices: left out
  printf 'ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n' > "$T/empty.ply"
  mlserver empty -i "$T/empty.ply" -o "$T/empty.obj" -s "$T/l.mlx" && expect_rc empty 255 &&
    expect_log empty "has no vertices: nothing to analyse"
  awk 'BEGIN { printf "ply\nformat ascii 1.0\nelement vertex 1600\nproperty float x\nproperty float y\nproperty float z\nend_header\n"
    for (i = 0; i < 1600; i++) printf "%g %g 0\n", (i % 40) / 40, int(i / 40) / 40 }' > "$T/plane.ply"
  mlserver plane -i "$T/plane.ply" -o "$T/plane.obj" -s "$T/l.mlx" && expect_rc plane 255 &&
    expect_log plane "no profile lines: layer 'plane.ply' has no directional feature points .*no layer was added"
  mlx "$T/long.mlx" "$(lines_xml minlen=100)"
  mlserver long -i "$T/cube.ply" -o "$T/long.obj" -s "$T/long.mlx" && expect_rc long 255 &&
    expect_log long "directional points of layer 'cube.ply' form no line longer than the minimum length"
  mlx "$T/beta.mlx" "$(lines_xml beta=0)"
  mlserver beta -i "$T/cube.ply" -o "$T/beta.obj" -s "$T/beta.mlx" && expect_rc beta 255 &&
    expect_log beta "the direction weight must be > 0 \\(got 0\\)"
  for r in empty plane long beta; do [[ -e "$T/$r.obj" ]] && fail "'$r': a failed run saved $r.obj"; done
  { printf 'ply\nformat ascii 1.0\nelement vertex 15004\nproperty float x\nproperty float y\nproperty float z\nend_header\nnan 0 0\n0 nan inf\n'
    sed '1,/^end_header/d' "$T/cube.ply"; } > "$T/nan.ply"
  if mlserver nan -i "$T/nan.ply" -o "$T/nan.obj" -s "$T/l.mlx"; then
    expect_rc nan 0
    expect_log nan "2 of 15004 vertices have NaN/Inf coordinates: they are left out \\(no line passes through them\\)"
    check_cube_lines "$T/nan.obj" 1 0.02 0 0 0 || fail "cube lines with NaN vertices (see above)"
  fi
  for r in empty plane long beta; do
    [[ -f "$T/$r.rc" ]] && log "$r: exit status $(cat "$T/$r.rc"): $(grep 'LOG: .*pointnpr:' "$T/$r.log" | tail -n 1)"
  done
  ;;

segment)
  # Segmentation of the library's clean test scene (tests/test_segment.c: ground plane, box,
  # sphere, cylinder, touching, 4 objects) with known labels: adjusted Rand index of the labels
  # (saved through vertex quality) against the truth >= 0.9, the bound of the library's own
  # tests for the clean scene; the segment mean colours give the same partition.
  scene_ply "$T/scene.ply" "$T/truth.txt" 11
  log "scene: $(wc -l < "$T/truth.txt") points"
  run_seg() { # NAME MIN_ARI SEGMENTS FILTER_XML
    local name=$1 min=$2 want=$3
    mlx "$T/$name.mlx" "$4"
    mlserver "$name" -i "$T/scene.ply" -o "$T/$name.ply" -m vc vq -s "$T/$name.mlx" || return 1
    expect_rc "$name" 0
    to_ascii "$T/$name.ply" "$T/$name-a.ply" || return 1
    score_segments "$T/$name-a.ply" "$T/truth.txt" "$name" "$min" "$want"
  }
  LAST_SCORE=""
  if run_seg jseg 0.9 0 "$(jseg_xml)"; then
    read -r qa qs ca cs <<< "$LAST_SCORE"
    # colours = segment mean colours: as many colours as segments, the same partition
    [[ "$cs" == "$qs" ]] && awk -v a="$qa" -v c="$ca" 'BEGIN { exit (a - c < 1e-3 && c - a < 1e-3) ? 0 : 1 }' ||
      fail "jseg: the colours ($cs, ARI $ca) are not one mean colour per segment ($qs, ARI $qa)"
    expect_log jseg "JSEG: [0-9]+ points \\([0-9]+ valid\\), [0-9]+ colour classes"
    expect_log jseg "stored per-vertex attribute segment \\(float label 0\\.\\.[0-9]+\\), vertex colours = segment mean colour, vertex quality = label"
  fi
  run_seg jseg4 0.9 4 "$(jseg_xml segments=4)" && expect_log jseg4 "region hierarchy cut \\(segment count\\): 4 segments"
  if run_seg rgbgrow 0.9 0 "$(grow_xml method=1)"; then
    # colours untouched without "colour by segment"
    paste -d ' ' <(sed '1,/^end_header/d' "$T/scene.ply" | awk '{ print $4, $5, $6 }') <(awk '{ print $5 }' "$T/scored.txt") |
      awk '{ if ($1 "," $2 "," $3 != $4) bad++ } END { exit bad ? 1 : 0 }' || fail "rgbgrow changed the colours without 'colour by segment'"
  fi
  # connected components: three spheres 1 apart (800 points each) and two far outliers, which
  # join their nearest kept component with a minimum size (the library test's known answer)
  awk -v truth="$T/spheres-truth.txt" 'BEGIN { PI = 3.14159265358979323846; n = 800
    print "ply\nformat ascii 1.0\nelement vertex 2402\nproperty float x\nproperty float y\nproperty float z\nend_header"
    for (b = 0; b < 3; b++) for (i = 0; i < n; i++) { z = 1 - 2 * (i + 0.5) / n; rr = sqrt(1 - z * z); phi = i * PI * (3 - sqrt(5))
      x = b + 0.3 * rr * cos(phi); y = 0.3 * rr * sin(phi); printf "%.7g %.7g %.7g\n", x, y, 0.3 * z; printf "%.7g %.7g %.7g %d\n", x, y, 0.3 * z, b > truth }
    print "5 5 5"; print "5 5 5 2" > truth; print "-5 5 5"; print "-5 5 5 0" > truth }' > "$T/spheres.ply"
  mlx "$T/cc.mlx" "$(grow_xml method=0 distance=0.15 minsize=10 color=true)"
  if mlserver cc -i "$T/spheres.ply" -o "$T/cc.ply" -m vc vq -s "$T/cc.mlx" && expect_rc cc 0 && to_ascii "$T/cc.ply" "$T/cc-a.ply"; then
    score_segments "$T/cc-a.ply" "$T/spheres-truth.txt" "components" 0.9999 3
    expect_log cc "vertex colours = one colour per segment"
  fi
  # robustness: JSEG / region growing without colours, an empty layer, a bad parameter: exit 255
  # with the message; NaN vertices: segment -1, success
  cube_ply "$T/cube.ply" 1 10 0 0 0
  mlx "$T/j.mlx" "$(jseg_xml)"
  mlserver nocolour -i "$T/cube.ply" -o "$T/nocolour.ply" -s "$T/j.mlx" && expect_rc nocolour 255 &&
    expect_log nocolour "layer 'cube.ply' has no per-vertex colour: JSEG segments by colour"
  mlx "$T/g.mlx" "$(grow_xml method=1)"
  mlserver nocolour2 -i "$T/cube.ply" -o "$T/nocolour2.ply" -s "$T/g.mlx" && expect_rc nocolour2 255 &&
    expect_log nocolour2 "has no per-vertex colour: colour region growing segments by colour"
  printf 'ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n' > "$T/empty.ply"
  mlserver empty -i "$T/empty.ply" -o "$T/empty-out.ply" -s "$T/j.mlx" && expect_rc empty 255 &&
    expect_log empty "has no vertices: nothing to analyse"
  mlx "$T/bad.mlx" "$(jseg_xml seed=0)"
  mlserver bad -i "$T/scene.ply" -o "$T/bad-out.ply" -s "$T/bad.mlx" && expect_rc bad 255 &&
    expect_log bad "the seed factor must be > 0 \\(got 0\\)"
  total=$(wc -l < "$T/truth.txt")
  { sed -n '1,/^end_header/p' "$T/scene.ply" | sed "s/^element vertex .*/element vertex $((total + 2))/"
    echo "nan 0 0 255 0 0"; echo "0 nan inf 0 255 0"; sed '1,/^end_header/d' "$T/scene.ply"; } > "$T/nan.ply"
  if mlserver nan -i "$T/nan.ply" -o "$T/nan-out.ply" -m vc vq -s "$T/j.mlx"; then
    expect_rc nan 0
    expect_log nan "2 of $((total + 2)) vertices have NaN/Inf coordinates: they are left out \\(segment -1\\)"
    expect_log nan "-1 for NaN/Inf vertices"
  fi
  for r in nocolour nocolour2 empty bad; do
    [[ -f "$T/$r.rc" ]] && log "$r: exit status $(cat "$T/$r.rc"): $(grep 'LOG: .*pointnpr:' "$T/$r.log" | tail -n 1)"
  done
  ;;

decorate)
  # The decorator "NPR render" in the MeshLab GUI: the GUI starts with both plugins, opens the
  # cube [0,1]^3 grid (h = 0.02, 15 002 points, no normals/colours), the plugin turns the
  # decoration on (test-only PNPR_MESHLAB_DECORATE_AT_START) and, on the 3rd frame with an
  # unchanged camera, reads MeshLab's framebuffer before (MeshLab's own rendering) and after its
  # draw (PNPR_MESHLAB_SNAPSHOT=PREFIX: PREFIX-plain/npr .png + .pgm, PREFIX-camera.txt with the
  # GL modelview, projection and viewport). The snapshots stay in the work folder (artifacts).
  [[ -n "$DECORATE" ]] || die "no decorate plugin given (5th argument)"
  [[ -x "$GUI_BIN" ]] || die "$GUI_BIN not found (packaging/install-deps.sh installs meshlab)"
  ln "$GUI_BIN" "$T/host/meshlab" 2> /dev/null || cp "$GUI_BIN" "$T/host/meshlab" || die "cannot copy $GUI_BIN"
  cube_ply "$T/cube.ply" 1 50 0 0 0
  geometry() { # gui + the cube's edge checks
    gui "$1" "$2" "$T/cube.ply" || return 1
    check_snapshot "$T/$1-camera.txt" "$T/$1-plain.pgm" "$T/$1-npr.pgm" "$1" || fail "'$1': snapshot checks (see above)"
  }
  geometry sketchy sketchy
  expect_log sketchy "features computed for the sketchy style \\(15002 points"
  geometry lines lines
  expect_log lines "pointnpr decorator: [0-9]+ profile lines"
  # a mesh layer (an RGB-D PLY with a range grid opens as one): the same cube with 5000 thin
  # triangles over its vertices is drawn as its vertices, with the point cube's edge checks
  awk 'NR == FNR { if ($0 == "end_header") { print "element face 5000"; print "property list uchar int vertex_indices" }
                   print; next }
       END { for (i = 0; i < 5000; i++) printf "3 %d %d %d\n", 3 * i, 3 * i + 1, 3 * i + 2 }' "$T/cube.ply" > "$T/cube_mesh.ply"
  if gui meshlayer sketchy "$T/cube_mesh.ply"; then
    check_snapshot "$T/meshlayer-camera.txt" "$T/meshlayer-plain.pgm" "$T/meshlayer-npr.pgm" meshlayer ||
      fail "'meshlayer': snapshot checks (see above)"
  fi
  # MeshLab restarts the decoration when a parameter is applied (GLArea::updateAllDecorators: end,
  # then start): the layers, features and upload are kept (one upload in the whole run), and the
  # frames after the restart still pass the edge checks
  GUI_ENV=(PNPR_MESHLAB_TEST_RESTART=1)
  if gui restart sketchy "$T/cube.ply"; then
    check_snapshot "$T/restart-camera.txt" "$T/restart-plain.pgm" "$T/restart-npr.pgm" restart ||
      fail "'restart': snapshot checks (see above)"
  fi
  GUI_ENV=()
  expect_log restart "pointnpr decorator: decoration restarted by MeshLab .*: layers, features and upload kept \\(1 upload\\(s\\) so far\\)"
  nup=$(grep -c "pointnpr decorator: uploaded" "$T/restart.log")
  [[ "$nup" == 1 ]] || fail "'restart': $nup uploads, expected 1 (the restart re-uploaded the cloud)"
  # A drag (synthetic mouse moves for 1 s, PNPR_MESHLAB_TEST_DRAG) with the moving frames forced to
  # the half-resolution preview (PNPR_MESHLAB_TEST_PREVIEW; unforced, a style whose moving frames stay
  # slow gets it): frames drawn while moving, every one a preview, no draw failure, the full frame
  # after the release
  GUI_ENV=(PNPR_MESHLAB_TEST_DRAG=1 PNPR_MESHLAB_TEST_PREVIEW=1) GUI_WAIT="$T/preview-drag.txt"
  gui preview sketchy "$T/cube.ply"
  GUI_ENV=() GUI_WAIT=''
  grep -q "pointnpr decorator: draw (.*) failed" "$T/preview.log" && fail "'preview': a draw failed"
  read -r pv_frames pv_half < <(sed -n 's/^drag: \([0-9]*\) frames in .*, \([0-9]*\) at half resolution.*/\1 \2/p' "$T/preview-drag.txt" 2> /dev/null)
  log "preview: $(cat "$T/preview-drag.txt" 2> /dev/null || echo "no drag figures")"
  holds preview "frames drawn while moving (>= 3), every one at half resolution" "${pv_frames:-0} >= 3 && ${pv_half:-0} == ${pv_frames:-1}"
  # MeshLab's info box over our frame: the same overlay as over its own (no GL state left changed)
  GUI_ENV=(PNPR_MESHLAB_TEST_INFOBOX="$T/infobox") GUI_WAIT="$T/infobox-host-npr.pgm"
  gui infobox sketchy "$T/cube.ply"
  GUI_ENV=() GUI_WAIT=''
  expect_log infobox "pointnpr decorator: info box frame 'plain' written"
  expect_log infobox "pointnpr decorator: info box frame 'npr' written"
  check_infobox "$T/infobox" || fail "'infobox': MeshLab's info box over the decorated frame is not the overlay it draws without it"
  # The plan's stages run on a worker thread: on a 240 002-point cube the viewport first shows
  # MeshLab's own points (nothing uploaded yet), MeshLab's progress bar moves, the event loop answers a synthetic event posted
  # when the computation starts while it still runs, and the frame after it passes the edge
  # checks. Then Esc (a synthetic key press once progress is reported) cancels: the run reports
  # it, the style's frame becomes plain points, MeshLab goes on.
  cube_ply "$T/cube200.ply" 1 200 0 0 0
  GUI_POINTS=240002 GUI_ENV=(PNPR_MESHLAB_TEST_EVENTS=1)
  if gui background sketchy "$T/cube200.ply"; then
    check_snapshot "$T/background-camera.txt" "$T/background-plain.pgm" "$T/background-npr.pgm" background ||
      fail "'background': snapshot checks (see above)"
  fi
  expect_log background "pointnpr decorator: computing features for the sketchy style in the background \\(240002 points\\): MeshLab's own points meanwhile, Esc cancels"
  nup=$(grep -c "pointnpr decorator: uploaded" "$T/background.log")
  [[ "$nup" == 1 ]] || fail "'background': $nup uploads, expected 1 (after the features)"
  expect_log background "pointnpr decorator: synthetic event answered after [0-9]+ ms while computing \\(features"
  expect_log background "pointnpr decorator: features computed for the sketchy style \\(240002 points, [0-9]+ ms\\)"
  bg=$(sed -n 's/.*background computation done after \([0-9]*\) ms: \([0-9]*\) progress reports, \([0-9]*\) progress bar updates, \([0-9]*\) event-loop.*/\1 \2 \3 \4/p' "$T/background.log" | head -n 1)
  log "background: ${bg:-no summary} (ms, progress reports, progress bar updates, event-loop ticks)"
  read -r bg_ms bg_rep bg_bar bg_ticks <<< "${bg:-0 0 0 0}"
  holds background "progress reported (>= 5) and shown in MeshLab's progress bar (>= 1), the event loop ticking (>= 1)" \
    "$bg_rep >= 5 && $bg_bar >= 1 && $bg_ticks >= 1"
  GUI_ENV=(PNPR_MESHLAB_TEST_CANCEL=1)
  gui cancel sketchy "$T/cube200.ply"
  GUI_ENV=() GUI_POINTS=
  expect_log cancel "pointnpr decorator: Esc: cancelling the computation"
  expect_log cancel "pointnpr decorator: feature analysis \\(.*\\) cancelled"
  expect_log cancel "pointnpr decorator: background computation cancelled after"
  expect_no_log cancel "features computed for the sketchy style"
  grep -q "^points 240002 drawn [1-9][0-9]* strokes 0\$" "$T/cancel-camera.txt" || fail "'cancel': the frame after the cancel is not plain points (strokes 0): $(grep ^points "$T/cancel-camera.txt")"
  # An aerial-like scene at first sight (issue: sketchy drew a 499k-point aerial scan as a black
  # shape): a rolling field of 360 000 jittered points (0.17 apart, colour noise) with 50 trees
  # (hemispheres of 2 000 points) and a tall mast, 460 200 points in all, in MeshLab's default
  # top view (fitted to the bounding box, so the field is small: about 12 points drawn per pixel;
  # the mast's box also makes the screen density's estimate of the covered pixels generous).
  # Default sketchy: ink (grey < 128) below half of the field's pixels (measured 0.21).
  aerial_ply "$T/aerial.ply"
  GUI_POINTS=460200
  gui aerial sketchy "$T/aerial.ply"
  GUI_POINTS=''
  ink_def=$(aerial_ink "$T/aerial-camera.txt" "$T/aerial-npr.pgm")
  log "aerial: ink of the field's pixels ${ink_def:-?}; $(grep ^points "$T/aerial-camera.txt" 2> /dev/null)"
  holds aerial "default sketchy not a black shape: ink < 0.5 of the field's pixels" "${ink_def:-1} < 0.5"
  expect_log meshlayer "pointnpr decorator: uploaded 15002 points from 1 layer\\(s\\) \\(1 mesh layer\\(s\\): their vertices\\)"
  ;;

stream)
  # A sample layer streamed by the view (docs/meshlab.md): a 400 000-point box, 2 x 2 x 20 along
  # z, at (5e5, 4.2e6, 100) in doubles, ordered for drawing; the GUI opens a uniform sample of
  # 20 000 of its points as offsets from that origin, which the test hooks place there by the
  # layer's Tr and mark as a sample of the ordered file (PNPR_MESHLAB_TEST_SAMPLE_OF and _ORIGIN,
  # as "NPR: Open a sample of a large PLY" makes its layer). MeshLab's first view looks down -z at
  # the box: its near end is about 3x closer than its far end. The decorator reads the view's
  # sample: about 20 000 points, every one a point of the file, the near fifth kept denser than the
  # far fifth by the ratio of the sums of 1/depth^2 over the file's points there (a share c / z^2,
  # the depths from the frame's modelview), where the uniform layer has them alike; the frame is
  # drawn from that sample. After a drag (the reads of the moving views cancelled), the sample of
  # the view where the camera rests, by the same measure. The same layer marked as a sample of the
  # file as written (not ordered): drawn as it is, said once.
  [[ -n "$DECORATE" ]] || die "no decorate plugin given (5th argument)"
  [[ -x "$GUI_BIN" ]] || die "$GUI_BIN not found (packaging/install-deps.sh installs meshlab)"
  ln "$GUI_BIN" "$T/host/meshlab" 2> /dev/null || cp "$GUI_BIN" "$T/host/meshlab" || die "cannot copy $GUI_BIN"
  # stream_scene NAME SEED HX HY HZ TOOL: 400 000 random points in the box of half-sides HX HY HZ
  # around (5e5, 4.2e6, 100), in doubles (NAME.txt.ply); TOOL (convert, or features) writes
  # NAME.ply, then NAME_lod.ply ordered for drawing; NAME_layer.ply: every 20th point as offsets
  # from that origin, and NAME.mlp, a project placing it there by its Tr
  stream_scene() {
    awk -v S="$2" -v hx="$3" -v hy="$4" -v hz="$5" 'function rnd() { S = (S * 16807) % 2147483647; return S / 2147483647 }
      BEGIN { n = 400000; print "ply\nformat ascii 1.0\nelement vertex " n
        print "property double x\nproperty double y\nproperty double z\nend_header"
        for (i = 0; i < n; i++) printf "%.3f %.3f %.3f\n", 500000 + hx * (2 * rnd() - 1), 4200000 + hy * (2 * rnd() - 1), 100 + hz * (2 * rnd() - 1) }' > "$T/$1.txt.ply"
    "$CLI" "$6" "$T/$1.txt.ply" -o "$T/$1.ply" --quiet && "$CLI" convert "$T/$1.ply" -o "$T/$1_lod.ply" --lod --quiet ||
      die "pointnpr $6 or convert --lod failed"
    awk '/^element vertex/ { $3 = 20000 } /^end_header/ { print; b = 1; next } !b { print; next }
      (++k % 20) == 0 { printf "%.3f %.3f %.3f\n", $1 - 500000, $2 - 4200000, $3 - 100 }' "$T/$1.txt.ply" > "$T/$1_layer.ply"
    printf '<!DOCTYPE MeshLabDocument>\n<MeshLabProject>\n <MeshGroup>\n  <MLMesh label="%s" filename="%s" visible="1">\n   <MLMatrix44>\n1 0 0 500000 \n0 1 0 4200000 \n0 0 1 100 \n0 0 0 1 \n</MLMatrix44>\n  </MLMesh>\n </MeshGroup>\n <RasterGroup/>\n</MeshLabProject>\n' \
      "$1_layer.ply" "$1_layer.ply" > "$T/$1.mlp"
  }
  stream_scene box 11 1 1 10 convert
  # stream_check NAME MIN: the sample streamed last is the view's of NAME's frame, its near/far
  # ratio at least MIN by 1/depth^2
  stream_check() {
    expect_log "$1" "pointnpr decorator: streamed [0-9]+ of the 400000 points of .*box_lod.ply for the view \\(20000 asked"
    expect_log "$1" "pointnpr decorator: uploaded [0-9]+ points from 1 layer\\(s\\).*'box_layer.ply' streamed for the view"
    local got
    got=$(sed -n 's/.*pointnpr decorator: streamed \([0-9]*\) of the 400000 points.*/\1/p' "$T/$1.log" | tail -n 1)
    grep -q "^points ${got:-x} drawn " "$T/$1-camera.txt" ||
      fail "'$1': the frame did not draw the streamed sample ($(grep ^points "$T/$1-camera.txt"), streamed ${got:-none})"
    to_ascii "$T/$1-sample.ply" "$T/$1-sample_a.ply" &&
      awk -v name="$1" -v min="$2" 'function key(a, b, c) { return sprintf("%.0f %.0f %.0f", a * 1000, b * 1000, c * 1000) }
        FILENAME ~ /camera.txt$/ { if ($1 == "modelview") for (k = 0; k < 16; k++) mv[k] = $(k + 2); next }
        /^end_header/ { b[FILENAME] = 1; next }
        !b[FILENAME] { next }
        FILENAME ~ /box.txt.ply$/ { inbox[key($1, $2, $3)] = 1; d = -(mv[2] * $1 + mv[6] * $2 + mv[10] * $3 + mv[14])
                                   if ($3 > 106) { wn += 1 / (d * d); fn++ } if ($3 < 94) { wf += 1 / (d * d); ff++ } next }
        { n++; if (!(key($1, $2, $3) in inbox)) bad++; if ($3 > 106) kn++; if ($3 < 94) kf++ }
        END { want = wn / wf; got = kn / (kf ? kf : 1)
              printf "%s: %d points, %d not in the file; near fifth %d, far fifth %d: ratio %.2f for %.2f by 1/depth^2 (file %d, %d)\n", name, n, bad, kn, kf, got, want, fn, ff
              exit (n > 17000 && n < 23000 && bad == 0 && want >= min && got > 0.85 * want && got < 1.15 * want) ? 0 : 1 }' \
        "$T/$1-camera.txt" "$T/box.txt.ply" "$T/$1-sample_a.ply" ||
      fail "'$1': the sample is not the view's (above)"
  }
  GUI_POINTS=20000
  GUI_ENV=(PNPR_MESHLAB_TEST_SAMPLE_OF="$T/box_lod.ply" PNPR_MESHLAB_TEST_SAMPLE_ORIGIN="500000 4200000 100"
           PNPR_MESHLAB_TEST_STREAM_OUT="$T/stream-sample.ply")
  gui stream points "$T/box.mlp" && stream_check stream 2
  # the file has no point_spacing: the sample's own is measured on the stream's thread, not in the
  # upload on MeshLab's
  expect_log stream "'box_layer.ply' streamed for the view, the sample's point spacing measured on the stream's thread"
  # the normals of the new sample are computed in the background, the first sample drawn meanwhile
  expect_log stream "computing features for the points style in the background \\(20000 points\\): MeshLab's own points meanwhile"
  expect_log stream "computing features for the points style in the background \\([0-9]+ points\\): the previous sample meanwhile"
  GUI_ENV=(PNPR_MESHLAB_TEST_SAMPLE_OF="$T/box_lod.ply" PNPR_MESHLAB_TEST_SAMPLE_ORIGIN="500000 4200000 100"
           PNPR_MESHLAB_TEST_STREAM_OUT="$T/drag-sample.ply" PNPR_MESHLAB_TEST_DRAG=1) GUI_WAIT="$T/drag-drag.txt"
  gui drag points "$T/box.mlp" && stream_check drag 0
  GUI_WAIT=''
  cmp -s "$T/stream-camera.txt" "$T/drag-camera.txt" && fail "'drag': the view did not change"
  # zoomed in (the wheel, 16 notches) on a plate of 400 000 points, 20 x 20 across the view, with
  # the features of pointnpr: the view's cone holds fewer points than the layer's 20 000, so the
  # stream holds every one of them: each point of the file inside the viewport, where the layer
  # has about a twentieth; the file's point spacing is uploaded (no kNN of the decorator's own)
  stream_scene plate 13 10 10 0.1 features
  GUI_ENV=(PNPR_MESHLAB_TEST_SAMPLE_OF="$T/plate_lod.ply" PNPR_MESHLAB_TEST_SAMPLE_ORIGIN="500000 4200000 100"
           PNPR_MESHLAB_TEST_STREAM_OUT="$T/zoom-sample.ply" PNPR_MESHLAB_TEST_WHEEL=16)
  if gui zoom points "$T/plate.mlp" && to_ascii "$T/zoom-sample.ply" "$T/zoom-sample_a.ply"; then
    awk 'FILENAME ~ /camera.txt$/ { if ($1 == "modelview") for (k = 0; k < 16; k++) mv[k] = $(k + 2)
                                    if ($1 == "projection") for (k = 0; k < 16; k++) pr[k] = $(k + 2); next }
      /^end_header/ { b[FILENAME] = 1; next }
      !b[FILENAME] { next }
      { x = $1; y = $2; z = $3; if (FILENAME ~ /layer.ply$/) { x += 500000; y += 4200000; z += 100 }
        for (r = 0; r < 4; r++) e[r] = mv[r] * x + mv[4 + r] * y + mv[8 + r] * z + mv[12 + r]
        for (r = 0; r < 4; r++) c[r] = pr[r] * e[0] + pr[4 + r] * e[1] + pr[8 + r] * e[2] + pr[12 + r] * e[3]
        inv = c[3] > 0 && c[0] <= c[3] && c[0] >= -c[3] && c[1] <= c[3] && c[1] >= -c[3]
        if (FILENAME ~ /plate.txt.ply$/) { fv += inv } else if (FILENAME ~ /layer.ply$/) { ln++; lv += inv } else { sn++; sv += inv } }
      END { printf "zoom: streamed %d points, %d in the viewport, of the file'"'"'s %d there; the layer %d, %d in it\n", sn, sv, fv, ln, lv
            exit (sn < 20000 && fv > 500 && sv == fv && lv < fv / 10) ? 0 : 1 }' \
      "$T/zoom-camera.txt" "$T/plate.txt.ply" "$T/plate_layer.ply" "$T/zoom-sample_a.ply" || fail "'zoom': the stream does not follow the zoomed view (above)"
    expect_log zoom "uploaded [0-9]+ points from 1 layer\\(s\\).*'plate_layer.ply' streamed for the view, point spacing from the file grown by the view's share"
  fi
  # two sample layers, the box and the plate in one project: both streamed, one read at a time
  # (each waits for the other's), the frame drawn from both
  sed -n '1,/<\/MLMesh>/p' "$T/box.mlp" > "$T/two.mlp"
  sed -n '/<MLMesh/,/<\/MLMesh>/p' "$T/plate.mlp" >> "$T/two.mlp"
  sed -n '/<\/MeshGroup>/,$p' "$T/box.mlp" >> "$T/two.mlp"
  GUI_POINTS=40000 GUI_LAYERS=2
  GUI_ENV=(PNPR_MESHLAB_TEST_SAMPLE_OF="$T/box_lod.ply;$T/plate_lod.ply" PNPR_MESHLAB_TEST_SAMPLE_ORIGIN="500000 4200000 100")
  if gui two points "$T/two.mlp"; then
    expect_log two "streamed [0-9]+ of the 400000 points of .*box_lod.ply for the view"
    expect_log two "streamed [0-9]+ of the 400000 points of .*plate_lod.ply for the view"
    expect_log two "uploaded [0-9]+ points from 2 layer\\(s\\).*'box_layer.ply', 'plate_layer.ply' streamed for the view"
  fi
  GUI_POINTS=20000 GUI_LAYERS=''
  # orthographic (MeshLab's Toggle Orthographic Camera after the first view was streamed): that
  # sample would lack what this view sees; the layer is drawn as it is, said
  GUI_ENV=(PNPR_MESHLAB_TEST_SAMPLE_OF="$T/box_lod.ply" PNPR_MESHLAB_TEST_SAMPLE_ORIGIN="500000 4200000 100"
           PNPR_MESHLAB_TEST_WHEEL=0 PNPR_MESHLAB_TEST_ORTHO=1)
  if gui ortho points "$T/box.mlp"; then
    expect_log ortho "the view of layer 'box_layer.ply' cannot be streamed \\(an orthographic view"
    grep -q "^points 20000 drawn " "$T/ortho-camera.txt" || fail "'ortho': not the layer's own points ($(grep ^points "$T/ortho-camera.txt"))"
    awk '$1 == "projection" { exit ($17 == 1 && $13 == 0) ? 0 : 1 }' "$T/ortho-camera.txt" || fail "'ortho': the view is not orthographic"
  fi
  GUI_ENV=(PNPR_MESHLAB_TEST_SAMPLE_OF="$T/box.ply" PNPR_MESHLAB_TEST_SAMPLE_ORIGIN="500000 4200000 100")
  gui unordered points "$T/box.mlp"
  expect_log unordered "layer 'box_layer.ply' is a sample of .*box.ply, which is not ordered for drawing: the layer is drawn as it is"
  expect_no_log unordered "streamed [0-9]+ of"
  [[ $(grep -c "pointnpr decorator: .*which is not ordered for drawing" "$T/unordered.log") == 1 ]] || fail "'unordered': not said once"
  # the file gone: said, the layer drawn as it is
  GUI_ENV=(PNPR_MESHLAB_TEST_SAMPLE_OF="$T/gone_lod.ply" PNPR_MESHLAB_TEST_SAMPLE_ORIGIN="500000 4200000 100")
  gui gone points "$T/box.mlp"
  expect_log gone "layer 'box_layer.ply' is a sample of .*gone_lod.ply, which is missing or not a regular file: the layer is drawn as it is"
  grep -q "^points 20000 drawn " "$T/gone-camera.txt" || fail "'gone': not the layer's own points"
  GUI_ENV=() GUI_POINTS=''
  ;;

decorate_styles)
  # The decorator's style and outline controls in the MeshLab GUI on a coloured cube
  # (colour_cube_ply: front face in a yellow and a blue half, colour noise +-30 per channel, no
  # normals, no segments): the stage plan of the library decides what is computed (cartoon on a
  # coloured cloud without labels: JSEG segments and, for the outline, normals). Runs: cartoon
  # with the defaults (style from the test hook; its settings file is the base of the others),
  # then from MeshLab's settings as the dialog saves them: cartoon with Outline = off, cartoon
  # with Outline width = 6 px, painterly; and sketchy of the colourless cube with the default tone
  # and with Tone gamma = 0.25. Frames stay in the work folder.
  [[ -n "$DECORATE" ]] || die "no decorate plugin given (5th argument)"
  [[ -x "$GUI_BIN" ]] || die "$GUI_BIN not found (packaging/install-deps.sh installs meshlab)"
  ln "$GUI_BIN" "$T/host/meshlab" 2> /dev/null || cp "$GUI_BIN" "$T/host/meshlab" || die "cannot copy $GUI_BIN"
  colour_cube_ply "$T/colour.ply"
  read -r INMY INSY INMB INSB < <(colour_stats "$T/colour.ply")
  log "input: yellow half grey $INMY sd $INSY, blue half grey $INMB sd $INSB (front-face points)"
  # measure NAME: the figures of run NAME into N_<NAME>_<FIGURE>
  measure() {
    local out
    out=$(measure_colour "$T/$1-camera.txt" "$T/$1-plain.pgm" "$T/$1-npr.pgm" "$1") || { fail "'$1': cannot measure the frame"; return 1; }
    eval "$(sed "s/\([A-Z]*\)=/N_$1_\1=/g" <<< "$out")"
  }

  # 1. cartoon, defaults: JSEG segments planned and computed, outlines along the silhouette, each
  #    half one flat colour (its mean), no ink at the colour boundary or inside
  gui cartoon cartoon "$T/colour.ply" && measure cartoon
  expect_log cartoon "pointnpr decorator: plan for the cartoon style: .*compute normals \\(outlines .*segments by JSEG \\(cartoon fills each colour segment"
  expect_log cartoon "pointnpr decorator: features computed for the cartoon style \\(15002 points, [0-9]+ ms\\): normals\$"
  expect_log cartoon "pointnpr decorator: [0-9]+ segments \\(JSEG, 15002 points"
  expect_log cartoon "pointnpr decorator: uploaded 15002 points from 1 layer\\(s\\), colours \\("
  nseg=$(sed -n 's/.*pointnpr decorator: \([0-9]*\) segments (JSEG.*/\1/p' "$T/cartoon.log" | head -n 1)
  log "cartoon: ${nseg:-no} JSEG segments"
  holds cartoon "JSEG finds the 3 colour regions (2 halves + the grey-green faces)" "${nseg:-0} == 3"
  holds cartoon ">= 90% of the silhouette samples inked" "${N_cartoon_EDGE:-0} >= 0.9 && ${N_cartoon_NEDGE:-0} >= 100"
  holds cartoon "yellow half flat (sd <= 1.5, input sd $INSY) at its mean colour (input $INMY +- 4)" \
    "${N_cartoon_SY:-99} <= 1.5 && ${N_cartoon_MY:-0} >= $INMY - 4 && ${N_cartoon_MY:-0} <= $INMY + 4"
  holds cartoon "blue half flat (sd <= 1.5, input sd $INSB) at its mean colour (input $INMB +- 4)" \
    "${N_cartoon_SB:-99} <= 1.5 && ${N_cartoon_MB:-0} >= $INMB - 4 && ${N_cartoon_MB:-0} <= $INMB + 4"
  holds cartoon "no outline at the colour boundary (<= 10% of its samples dark), no ink inside (<= 1%)" \
    "${N_cartoon_SEAM:-1} <= 0.1 && ${N_cartoon_DARKIN:-1} <= 0.01 && ${N_cartoon_NIN:-0} >= 500"
  holds cartoon "paper-white background, >= 25% of the pixels restyled" "${N_cartoon_BG:-0} == 255 && ${N_cartoon_DIFFER:-0} >= 0.25"

  # the dialog's parameters as MeshLab saved them (the base of the runs below)
  BASECONF=$(find "$T/home-cartoon/.config" -name '*.conf' | head -n 1)
  [[ -f "$BASECONF" ]] || die "MeshLab wrote no settings file under $T/home-cartoon/.config"
  conf_has() { grep -q "^PointNPR%3A%3A$1=.*$2" "$BASECONF" || fail "settings: PointNPR::$1 lacks /$2/"; }
  conf_has Look 'enum_val5=\\"comic\\"'
  conf_has DrawStyle 'enum_cardinality=\\"8\\"'
  conf_has DrawStyle 'enum_val5=\\"painterly\\"'
  conf_has DrawStyle 'enum_val6=\\"brush\\"'
  conf_has DrawStyle 'enum_val7=\\"hierarchy\\"'
  conf_has TonalArtMap 'enum_val1=\\"hatch\\"'
  # the dialog's defaults are the library's tables, as `pointnpr options` prints them
  table_default() { "$CLI" options --markdown | awk -F' [|] ' -v o="\`--$1\`" '$1 == "| " o {print $3}'; }
  for pair in Abstraction:hier-abstraction StrokeSize:stroke-px BrushScale:brush-scale LineWidth:line-width; do
    d=$(table_default "${pair#*:}")
    [[ -n "$d" ]] || fail "pointnpr options lacks --${pair#*:}"
    conf_has "${pair%%:*}" ' value=\\"'"$d"'\\"'
  done
  conf_has Brush 'enum_val0=\\"bristle\\"'
  conf_has Brush 'enum_val2=\\"round\\"'
  conf_has DrawStyle ' value=\\"1\\"'
  conf_has Outline 'enum_cardinality=\\"3\\"'
  conf_has Outline 'enum_val2=\\"off\\"'
  conf_has Outline 'on for cartoon 2.5 px, lines 2.5 px'
  conf_has OutlineWidth 'type=\\"RichFloat\\"'
  conf_has OutlineWidth ' value=\\"0\\"'
  conf_has OutlineWidth "0 = the style's default (cartoon 2.5 px, lines 2.5 px)"
  conf_has ToneSource 'enum_cardinality=\\"4\\"'
  conf_has ToneSource 'enum_val3=\\"both\\"'
  conf_has ToneGamma ' value=\\"0\\"'
  conf_has ToneGamma '0 = library default'
  grep "^PointNPR%3A%3A" "$BASECONF" | sed 's/=.* description=\\"\([^\\]*\)\\".*/: \1/'

  # 2. Outline = off (settings): the silhouette loses its ink, the fills stay
  gui nooutline cartoon "$T/colour.ply" DrawStyle=3 Outline=2 && measure nooutline
  expect_log nooutline "pointnpr decorator: plan for the cartoon style: segments by JSEG"
  holds nooutline "<= 10% of the silhouette samples dark (outline on: ${N_cartoon_EDGE:-?})" "${N_nooutline_EDGE:-1} <= 0.1"
  holds nooutline "the outline bands lose >= 90% of their dark pixels (${N_cartoon_BAND:-?} with the outline)" \
    "${N_nooutline_BAND:-1e9} <= 0.1 * ${N_cartoon_BAND:-0} && ${N_cartoon_BAND:-0} >= 200"
  holds nooutline "the same flat fills (means within 2 grey levels of the outlined frame's)" \
    "${N_nooutline_SY:-99} <= 1.5 && ${N_nooutline_SB:-99} <= 1.5 && (${N_nooutline_MY:-0} - ${N_cartoon_MY:-0})^2 <= 4 && (${N_nooutline_MB:-0} - ${N_cartoon_MB:-0})^2 <= 4"

  # 3. Outline width = 6 px (settings) against the style's default (2.5 px)
  gui wide cartoon "$T/colour.ply" DrawStyle=3 OutlineWidth=6 && measure wide
  holds wide "silhouette inked (>= 90%)" "${N_wide_EDGE:-0} >= 0.9"
  holds wide "6 px outline bands hold 1.8..3.6 x the dark pixels of the default width (${N_cartoon_BAND:-?})" \
    "${N_wide_BAND:-0} >= 1.8 * ${N_cartoon_BAND:-1e9} && ${N_wide_BAND:-1e9} <= 3.6 * ${N_cartoon_BAND:-0}"

  # A painting style's frame (painterly, brush, hierarchy): no draw failure, each half painted near its input
  # grey, no paper or ink inside, paper-white around, most pixels restyled.
  painted() {
    local n=$1 my="N_$1_MY" mb="N_$1_MB" dark="N_$1_DARKIN" nin="N_$1_NIN" bg="N_$1_BG" differ="N_$1_DIFFER"
    grep -q "pointnpr decorator: draw ($n) failed" "$T/$n.log" && fail "'$n': the draw failed"
    holds "$n" "yellow half painted near its colour (grey $INMY +- 20), blue half too ($INMB +- 20)" \
      "(${!my:-0} - $INMY)^2 <= 400 && (${!mb:-0} - $INMB)^2 <= 400"
    holds "$n" "no paper or ink inside: <= 2% dark samples" "${!dark:-1} <= 0.02 && ${!nin:-0} >= 500"
    holds "$n" "paper-white background, >= 25% of the pixels restyled" "${!bg:-0} == 255 && ${!differ:-0} >= 0.25"
  }
  # 4. painterly (settings): features planned and computed, dabs in the points' colours
  gui painterly painterly "$T/colour.ply" DrawStyle=5 && measure painterly
  expect_log painterly "pointnpr decorator: plan for the painterly style: compute feature degree .*compute feature classes"
  expect_log painterly "pointnpr decorator: features computed for the painterly style \\(15002 points, [0-9]+ ms\\): feature degree, feature classes\$"
  painted painterly
  # 4b. brush (settings): the brush stage planned and run, strokes in the points' colours
  gui brush brush "$T/colour.ply" DrawStyle=6 && measure brush
  expect_log brush "pointnpr decorator: plan for the brush style: .*brush sizes and clusters"
  expect_log brush "pointnpr decorator: brush strokes prepared \\([0-9]+ colour clusters, 15002 points, [0-9]+ ms\\)"
  painted brush
  # 4c. hierarchy (settings): the sphere tree planned and built, strokes in the regions' colours
  gui hierarchy hierarchy "$T/colour.ply" DrawStyle=7 && measure hierarchy
  expect_log hierarchy "pointnpr decorator: plan for the hierarchy style: .*sphere hierarchy"
  expect_log hierarchy "pointnpr decorator: sphere hierarchy built \\([0-9]+ leaves, [0-9]+ regions, 15002 points, [0-9]+ ms\\)"
  painted hierarchy
  # 4d. hierarchy with the hatch map (settings): ink hatching on paper, the lit front face light
  gui hierhatch hierarchy "$T/colour.ply" DrawStyle=7 TonalArtMap=1 && measure hierhatch
  grep -q "pointnpr decorator: draw (hierhatch) failed" "$T/hierhatch.log" && fail "'hierhatch': the draw failed"
  holds hierhatch "hatching leaves paper between its strokes: lighter than the painted frame (${N_hierarchy_MY:-?})" \
    "${N_hierhatch_MY:-0} > ${N_hierarchy_MY:-255} + 10"

  # 5. Tone gamma (settings) reaches the dithering points: sketchy on the colourless cube, whose
  #    front face is lit (light tone: few hatches at the library's default curve); gamma 0.25
  #    lifts the light tones (t^0.25), so many more dithering points hatch the face
  cube_ply "$T/cube.ply" 1 50 0 0 0
  gui sketchy sketchy "$T/cube.ply" DrawStyle=1 && measure sketchy
  gui darktone sketchy "$T/cube.ply" DrawStyle=1 ToneGamma=0.25 && measure darktone
  expect_log sketchy "pointnpr decorator: features computed for the sketchy style \\(15002 points, [0-9]+ ms\\): feature degree, feature classes, dithering points\$"
  expect_log darktone "pointnpr decorator: features computed for the sketchy style \\(15002 points, [0-9]+ ms\\): feature degree, feature classes, dithering points\$"
  holds sketchy "default tone: <= 5% of the front face's samples dark" "${N_sketchy_DARKIN:-1} <= 0.05 && ${N_sketchy_NIN:-0} >= 500"
  holds darktone "tone gamma 0.25: >= 10% of the front face's samples dark and >= 4x the default tone's (${N_sketchy_DARKIN:-?})" \
    "${N_darktone_DARKIN:-0} >= 0.1 && ${N_darktone_DARKIN:-0} >= 4 * ${N_sketchy_DARKIN:-1}"

  # 6. image-space effects (docs/effects.md). The cartoon preset from the settings (Effects = 1,
  #    the library's first preset) over the points style: one layer (no labels), the toon's
  #    outline from the layer's coverage inks the silhouette, the paper stays white. Then pipeline
  #    files through the test hook PNPR_MESHLAB_TEST_EFFECTS=file:PATH: `preset ink` draws the
  #    silhouette on paper (the faces white inside); a bad file is reported with FILE:LINE and the
  #    style is drawn without effects (no crash).
  gui fxcartoon points "$T/colour.ply" DrawStyle=0 Effects=1 && measure fxcartoon
  expect_log fxcartoon "pointnpr decorator: effects: preset cartoon, 1 node\\(s\\), layering inpainted"
  expect_log fxcartoon "pointnpr decorator: effects frame: 1 layers of [0-9]+x[0-9]+"
  holds fxcartoon ">= 80% of the silhouette samples inked" "${N_fxcartoon_EDGE:-0} >= 0.8 && ${N_fxcartoon_NEDGE:-0} >= 100"
  holds fxcartoon "paper-white background, >= 25% of the pixels restyled" "${N_fxcartoon_BG:-0} == 255 && ${N_fxcartoon_DIFFER:-0} >= 0.25"
  printf 'preset ink\n' > "$T/ink.fx"
  PNPR_MESHLAB_TEST_EFFECTS="file:$T/ink.fx" gui fxink points "$T/colour.ply" && measure fxink
  expect_log fxink "pointnpr decorator: effects: $T/ink.fx, 1 node\\(s\\)"
  holds fxink ">= 80% of the silhouette samples inked" "${N_fxink_EDGE:-0} >= 0.8"
  holds fxink "the yellow half drawn as paper (mean grey >= 230)" "${N_fxink_MY:-0} >= 230"
  printf 'node a labels 1\ntoon levels=99\n' > "$T/bad.fx"
  PNPR_MESHLAB_TEST_EFFECTS="file:$T/bad.fx" gui fxbad points "$T/colour.ply"
  expect_log fxbad "pointnpr decorator: effects file: .*bad.fx:2: .*levels.*; drawn without"

  # 6b. a look (the library's looks, pointnpr render --look) from the settings: Look = comic (the
  #    5th look): the cartoon style planned and drawn, flat fills, and outlines at the look's 3.5 px
  #    (more outline ink than the cartoon default's 2.5 px)
  nlook=$("$CLI" render --help 2>&1 | tr -d '\n' | sed -n 's/.*(\(pencil[^)]*\)).*/\1/p' | tr -s ' ' | tr '|' '\n' | awk '{$1=$1} $0 == "comic" {print NR}')
  gui lookcomic cartoon "$T/colour.ply" Look="${nlook:-0}" && measure lookcomic
  expect_log lookcomic "pointnpr decorator: plan for the cartoon style: .*segments by JSEG"
  holds lookcomic "comic look: cartoon's flat fills (sd <= 1.5) and silhouette (>= 90%), more outline ink than cartoon's default (${N_cartoon_BAND:-?})" \
    "${N_lookcomic_SY:-99} <= 1.5 && ${N_lookcomic_EDGE:-0} >= 0.9 && ${N_lookcomic_BAND:-0} >= 1.2 * ${N_cartoon_BAND:-1e9}"

  # 7. a style per layer (the filter "NPR: Set layer style"; here the test hook writes the same
  #    per-mesh attribute): the coloured cube in cartoon and a copy 1.2 to its right in points, the
  #    decoration's Style sketchy (drawn nowhere). One frame, one plan for both styles: the left
  #    cube's halves flat at their mean colours (cartoon's fills), the right cube's keep the points'
  #    colour noise, each near its input grey.
  awk '/^end_header/ { print; b = 1; next } b { $1 += 1.2 } { print }' "$T/colour.ply" > "$T/colour_right.ply"
  GUI_INPUTS=("$T/colour_right.ply") GUI_POINTS=30004 GUI_LAYERS=2 GUI_ENV=(PNPR_MESHLAB_TEST_LAYER_STYLES=cartoon,points)
  gui layers sketchy "$T/colour.ply"
  GUI_INPUTS=() GUI_POINTS='' GUI_LAYERS='' GUI_ENV=()
  expect_log layers "pointnpr decorator: styles per layer: 'colour.ply' cartoon, 'colour_right.ply' points"
  expect_log layers "pointnpr decorator: plan for the points and cartoon style: .*segments by JSEG"
  grep -q "pointnpr decorator: draw (.*) failed" "$T/layers.log" && fail "'layers': the draw failed"
  measure_sides layers N
  # the inner halves (the view may cut the outer ones): the left cube's blue, the right cube's yellow
  holds layers "left cube (cartoon): its blue half flat (sd <= 1.5) at its mean (+- 4 of $INMB)" \
    "${N_left_SB:-99} >= 0 && ${N_left_SB:-99} <= 1.5 && (${N_left_MB:-0} - $INMB)^2 <= 16 && ${N_left_NIN:-0} >= 500"
  holds layers "right cube (points): its yellow half keeps the colour noise (sd >= half the input's $INSY) near its grey (+- 10)" \
    "${N_right_SY:-0} >= 0.5 * $INSY && (${N_right_MY:-0} - $INMY)^2 <= 100 && ${N_right_NIN:-0} >= 500"

  # 7b. each layer's own feature classes: two colourless cubes side by side in sketchy without
  #    outlines (settings); the first carries the features filter's attributes, every point class
  #    0 (test hook PNPR_MESHLAB_TEST_LAYER_CLASS), the second none. The plan computes classes for
  #    the merged cloud and the first layer's own replace them at its points: the first cube gets
  #    no strokes (its silhouette samples <= 10% dark, nothing inside), the second its edge strokes
  awk '/^end_header/ { print; b = 1; next } b { $1 += 1.2 } { print }' "$T/cube.ply" > "$T/cube_right.ply"
  GUI_INPUTS=("$T/cube_right.ply") GUI_POINTS=30004 GUI_LAYERS=2 GUI_ENV=(PNPR_MESHLAB_TEST_LAYER_CLASS=0)
  gui ownclass sketchy "$T/cube.ply" DrawStyle=1 Outline=2
  GUI_INPUTS=() GUI_POINTS='' GUI_LAYERS='' GUI_ENV=()
  expect_log ownclass "pointnpr decorator: uploaded 30004 points from 2 layer.*feature classes from 'cube.ply''s attributes \\(computed for the others\\)"
  measure_sides ownclass O
  holds ownclass "the first cube keeps its own classes (none: <= 10% of its silhouette samples dark, no ink inside), the second its computed edge strokes (>= 50%)" \
    "${O_left_EDGE:-1} <= 0.1 && ${O_left_DARKIN:-1} == 0 && ${O_left_NEDGE:-0} >= 50 && ${O_right_EDGE:-0} >= 0.5 && ${O_right_NEDGE:-0} >= 50"

  # 8. a style map file (the panel's Style map, as pointnpr render --style-map; here through the
  #    test hook PNPR_MESHLAB_TEST_STYLE_MAP): segments 0 and 1 in points, the others in cartoon, on
  #    the coloured cube (JSEG planned for cartoon: its 3 segments). One frame: at least one half of
  #    the front face keeps its colour noise (points), the log names the map. A bad file: its
  #    FILE:LINE in the log, the frame drawn without it (in the Style).
  printf '0 points\n1 points\n* cartoon\n' > "$T/map.txt"
  PNPR_MESHLAB_TEST_STYLE_MAP="$T/map.txt" gui smap sketchy "$T/colour.ply" && measure smap
  expect_log smap "pointnpr decorator: style map: .*map.txt, 2 entries, others cartoon"
  expect_log smap "pointnpr decorator: plan for the points and cartoon style: .*segments by JSEG"
  grep -q "pointnpr decorator: draw (.*) failed" "$T/smap.log" && fail "'smap': the draw failed"
  holds smap "a half drawn as points keeps the colour noise (sd >= half the input's $INSY / $INSB)" \
    "${N_smap_SY:-0} >= 0.5 * $INSY || ${N_smap_SB:-0} >= 0.5 * $INSB"
  printf '0 crayon\n' > "$T/badmap.txt"
  PNPR_MESHLAB_TEST_STYLE_MAP="$T/badmap.txt" gui badmap sketchy "$T/colour.ply"
  expect_log badmap "pointnpr decorator: style map file: .*badmap.txt:1: .*; drawn without"
  ;;

streampic)
  # Not a test (no ctest entry): the picture of docs/meshlab.md, "A sample layer streamed by the
  # view". PNPR_STREAM_INPUT: a PLY ordered for drawing (pointnpr convert --lod); a uniform sample
  # of a twentieth of its points (x y z red green blue, offsets from PNPR_STREAM_ORIGIN="X Y Z",
  # placed there by a project file's Tr) opened in the GUI, zoomed in by PNPR_STREAM_WHEEL notches
  # (default 8), drawn in PNPR_STREAM_STYLE (default sketchy): snapshots streampic-layer-npr.png
  # (the layer as it is) and streampic-stream-npr.png (streamed). PNPR_STREAM_LAYER: a layer PLY
  # made beforehand instead (its positions offsets from that origin), for a file too large for an
  # ascii pass.
  [[ -n "$DECORATE" && -f "${PNPR_STREAM_INPUT:-}" ]] ||
    die "usage: PNPR_STREAM_INPUT=FILE.ply PNPR_STREAM_ORIGIN='X Y Z' run.sh streampic PLUGIN CLI WORKDIR DECORATE"
  ln "$GUI_BIN" "$T/host/meshlab" 2> /dev/null || cp "$GUI_BIN" "$T/host/meshlab" || die "cannot copy $GUI_BIN"
  read -r ox oy oz <<< "${PNPR_STREAM_ORIGIN:-0 0 0}"
  if [[ -f "${PNPR_STREAM_LAYER:-}" ]]; then # a layer made beforehand (a large file: no ascii pass)
    ln -s "$PNPR_STREAM_LAYER" "$T/layer.ply"
  else
    to_ascii "$PNPR_STREAM_INPUT" "$T/input_a.ply" || die "cannot read $PNPR_STREAM_INPUT"
    awk -v ox="$ox" -v oy="$oy" -v oz="$oz" '/^element vertex/ { n = $3 } /^property/ && !b { col[$NF] = np++ }
      /^end_header/ { b = 1; m = int(n / 20); print "ply\nformat ascii 1.0\nelement vertex " m
        print "property float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header"; next }
      b && (++k % 20) == 0 && k <= 20 * m { printf "%.3f %.3f %.3f %d %d %d\n", $1 - ox, $2 - oy, $3 - oz, $(col["red"] + 1), $(col["green"] + 1), $(col["blue"] + 1) }' \
      "$T/input_a.ply" > "$T/layer.ply"
  fi
  printf '<!DOCTYPE MeshLabDocument>\n<MeshLabProject>\n <MeshGroup>\n  <MLMesh label="layer.ply" filename="layer.ply" visible="1">\n   <MLMatrix44>\n1 0 0 %s \n0 1 0 %s \n0 0 1 %s \n0 0 0 1 \n</MLMatrix44>\n  </MLMesh>\n </MeshGroup>\n <RasterGroup/>\n</MeshLabProject>\n' "$ox" "$oy" "$oz" > "$T/layer.mlp"
  GUI_POINTS=$(grep -a -m 1 '^element vertex' "$T/layer.ply" | awk '{ print $3 }')
  GUI_ENV=(PNPR_MESHLAB_TEST_WHEEL="${PNPR_STREAM_WHEEL:-8}")
  gui streampic-layer "${PNPR_STREAM_STYLE:-sketchy}" "$T/layer.mlp"
  GUI_ENV=(PNPR_MESHLAB_TEST_WHEEL="${PNPR_STREAM_WHEEL:-8}" PNPR_MESHLAB_TEST_SAMPLE_OF="$PNPR_STREAM_INPUT"
           PNPR_MESHLAB_TEST_SAMPLE_ORIGIN="$ox $oy $oz")
  gui streampic-stream "${PNPR_STREAM_STYLE:-sketchy}" "$T/layer.mlp"
  grep -h "streamed\|^points" "$T/streampic-stream.log" "$T"/streampic-*-camera.txt
  ;;

drag)
  # Not a test (no ctest entry): the frame rates of docs/meshlab.md. The GUI on PNPR_DRAG_INPUT (a
  # PLY), the decorator in each of PNPR_DRAG_STYLES (default "points sketchy"): once a frame at
  # rest is drawn (the features computed), the test hook PNPR_MESHLAB_TEST_DRAG drags the
  # trackball for 2 s with synthetic mouse moves and prints the frames drawn meanwhile and when
  # the full-budget frame follows the release.
  [[ -n "$DECORATE" && -f "${PNPR_DRAG_INPUT:-}" ]] || die "usage: PNPR_DRAG_INPUT=FILE.ply run.sh drag PLUGIN CLI WORKDIR DECORATE"
  ln "$GUI_BIN" "$T/host/meshlab" 2> /dev/null || cp "$GUI_BIN" "$T/host/meshlab" || die "cannot copy $GUI_BIN"
  GUI_POINTS=$(awk '/^element vertex/ { print $3; exit }' "$PNPR_DRAG_INPUT")
  for style in ${PNPR_DRAG_STYLES:-points sketchy}; do
    GUI_ENV=(PNPR_MESHLAB_TEST_DRAG=2) GUI_WAIT="$T/drag-$style-drag.txt"
    gui "drag-$style" "$style" "$PNPR_DRAG_INPUT"
    log "$style, $GUI_POINTS points: $(cat "$T/drag-$style-drag.txt" 2> /dev/null || echo "no figures")"
  done
  ;;

snapshot)
  # MeshLab's own File > Save snapshot with the decorator on, on the sample scan (the lion case's
  # cached WORKDIR/lion.ply, fetched + converted once): the GUI opens the lion, the plugin turns
  # "NPR render" on (sketchy, PNPR_MESHLAB_DECORATE_AT_START), takes its own frame pair
  # (PNPR_MESHLAB_SNAPSHOT: MeshLab's plain frame + the NPR frame, camera), then
  # (PNPR_MESHLAB_TEST_SAVE_SNAPSHOT) triggers MeshLab's "Save snapshot" action, fills its dialog
  # (folder, base name, screen multiplier 2) and clicks Save: MeshLab renders 2x2 tiles with
  # off-centre frusta and writes meshlab_snapshot00.png itself (kept in the work folder).
  [[ -n "$DECORATE" ]] || die "no decorate plugin given (5th argument)"
  [[ -x "$GUI_BIN" ]] || die "$GUI_BIN not found (packaging/install-deps.sh installs meshlab)"
  command -v convert > /dev/null || die "ImageMagick convert not found (reads the PNG snapshot)"
  ln "$GUI_BIN" "$T/host/meshlab" 2> /dev/null || cp "$GUI_BIN" "$T/host/meshlab" || die "cannot copy $GUI_BIN"
  CACHE="$WORK/sample-cache"
  LION="$WORK/lion.ply"
  if [[ ! -s "$LION" ]]; then
    tiles=$(bash "$SRC/scripts/fetch-sample.sh" "$CACHE" | tail -n 1) ||
      die "could not fetch the sample scan (scripts/fetch-sample.sh $CACHE): this test needs it"
    "$CLI" convert "$tiles" -o "$LION" --quiet || die "pointnpr convert of $tiles failed" # written whole or not at all
  fi
  SNAP="$T/meshlab_snapshot00.png"
  SNAP_FACTOR=${SNAP_FACTOR:-3} # 3: its middle tile is symmetric, as the view is (the decorator must still tell it)
  rm -f "$SNAP" "$T"/lion-*
  mkdir -p "$T/home"
  (cd "$T" && HOME="$T/home" XDG_RUNTIME_DIR="$T/home" PNPR_MESHLAB_DECORATE_AT_START=1 \
    PNPR_MESHLAB_SNAPSHOT="$T/lion" PNPR_MESHLAB_TEST_STYLE="${SNAP_STYLE:-sketchy}" PNPR_MESHLAB_TEST_SAVE_SNAPSHOT="$T" \
    PNPR_MESHLAB_TEST_SNAPSHOT_FACTOR="$SNAP_FACTOR" \
    LD_LIBRARY_PATH="$MLLIB${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" exec timeout 170 "$T/host/meshlab" "$LION") \
    > "$T/gui.log" 2>&1 &
  pid=$!
  prev=-1
  for i in $(seq 1 1500); do
    if [[ -s "$SNAP" ]]; then # written by QImage::save: wait until its size is stable
      sz=$(stat -c %s "$SNAP"); [[ "$sz" == "$prev" ]] && break; prev=$sz
    fi
    kill -0 "$pid" 2> /dev/null || break
    sleep 0.1
  done
  sleep 0.5
  if kill -0 "$pid" 2> /dev/null; then
    kill "$pid"; wait "$pid" 2> /dev/null
  else
    wait "$pid"; fail "MeshLab exited by itself (status $?) before it was stopped"
  fi
  grep -qE "Segmentation fault|Aborted|core dumped|terminate called|Assertion .* failed" "$T/gui.log" && { fail "MeshLab crashed:"; tail -n 20 "$T/gui.log"; }
  no_plugin_errors gui
  expect_log gui "Enabled Decorate mode NPR render"
  expect_log gui "pointnpr decorator: uploaded [0-9]+ points from 1 layer"
  expect_log gui "pointnpr decorator: snapshot .* written"
  expect_log gui "pointnpr decorator: test: Save snapshot dialog accepted \\(folder .*, multiplier $SNAP_FACTOR\\)"
  expect_log gui "pointnpr decorator: snapshot tiles at ${SNAP_FACTOR}x the view: the points of the view on screen, widths ${SNAP_FACTOR}x"
  grep "pointnpr decorator:" "$T/gui.log"
  [[ -s "$SNAP" ]] || die "MeshLab's Save snapshot wrote no $SNAP (log: $T/gui.log)"
  [[ -f "$T/lion-camera.txt" && -f "$T/lion-plain.pgm" ]] || die "no decorator frame pair (log: $T/gui.log)"
  read -r _ _ _ vw vh < <(grep '^viewport' "$T/lion-camera.txt")
  convert "$SNAP" -colorspace gray -depth 8 -compress none pgm:"$T/snapshot.pgm" || die "convert $SNAP failed"
  # the snapshot: exactly F x the viewport; paper-white corners; >= 50% light (> 200) pixels and
  # >= 1% dark (< 110) stroke pixels; >= 25% of its pixels differ by > 40 grey levels from MeshLab's
  # own (undecorated) frame scaled F x (the plain frame's background is MeshLab's gradient)
  awk -v vw="$vw" -v vh="$vh" -v F="$SNAP_FACTOR" '
    FNR == 1 { f++ }
    f == 1 { if (FNR == 2) { PW = $1; PH = $2 } if (FNR > 3) for (c = 1; c <= NF; c++) pl[n1++] = $c; next }
    { for (c = 1; c <= NF; c++) { k++
        if (k == 2) W = $c + 0; if (k == 3) H = $c + 0
        if (k > 4) { v = $c; i = k - 5; x = i % W; y = int(i / W); n++
          if (v < 110) dark++; if (v > 200) light++
          p = pl[int(y / F) * PW + int(x / F)]; d = v - p; if (d > 40 || d < -40) differ++
          if ((x == 0 || x == W - 1) && (y == 0 || y == H - 1)) { corners++; if (v == 255) white++ } } } }
    END {
      printf "snapshot %dx%d (viewport %dx%d, plain frame %dx%d): %.1f%% dark, %.1f%% light, %.1f%% differ from the plain frame, %d of %d corners white\n",
             W, H, vw, vh, PW, PH, 100 * dark / n, 100 * light / n, 100 * differ / n, white, corners
      bad = 0
      if (W != F * vw || H != F * vh || n != W * H) { print "wrong size"; bad++ }
      if (PW != vw || PH != vh) { print "plain frame size differs from the viewport"; bad++ }
      if (dark < 0.01 * n || light < 0.5 * n) { print "not dark strokes on light paper"; bad++ }
      if (differ < 0.25 * n) { print "too close to the plain frame"; bad++ }
      if (white != 4) { print "corners are not paper white"; bad++ }
      exit bad ? 1 : 0 }' "$T/lion-plain.pgm" "$T/snapshot.pgm" || fail "snapshot checks (see above)"
  # seamless and the same drawing: every row and column along a tile border is at most 1.5 x (+ 1%)
  # as dark (< 128) as the darkest of the rows / columns 3 and 4 px from it (a dashed seam would
  # double it: an injected 1 px line fails this); the hard jumps (> 100 grey levels) across a
  # tile border are at most 1.5 x (+ 10) those across the neighbouring lines 2..4 px away (marks
  # cut at the border: 73 against 10..29 before the guard band); the snapshot's ink share is 0.6 .. 1.6 x that
  # of the decorator's frame on screen (widths scaled with the multiplier; unscaled 0.47 .. 0.67)
  awk -v F="$SNAP_FACTOR" '
    function pgm(v) { k++; if (k == 2) W = v + 0; if (k == 3) H = v + 0; return k > 4 }
    FNR == 1 { f++; k = 0 }
    f == 1 { for (c = 1; c <= NF; c++) if (pgm($c)) { sn++; if ($c < 128) sd++ } next }
    { for (c = 1; c <= NF; c++) if (pgm($c)) { i = k - 5; x = i % W; y = int(i / W); n++; v = $c + 0
        if (v < 128) { dark++; col[x]++; row[y]++ }
        # hard jumps (> 100 grey levels) between neighbouring columns / rows: a mark cut at a border
        if (x > 0 && (v - prev > 100 || prev - v > 100)) cj[x]++
        if (y > 0 && (v - up[x] > 100 || up[x] - v > 100)) rj[y]++
        prev = v; up[x] = v } }
    END {
      bad = 0; tw = W / F; th = H / F
      for (b = 1; b < F; b++) for (e = 0; e < 2; e++) {
        x = b * tw - 1 + e; near = 0
        for (d = 3; d <= 4; d++) { near = col[x - d] > near ? col[x - d] : near; near = col[x + d] > near ? col[x + d] : near }
        if (col[x] / H > 1.5 * near / H + 0.01) { printf "seam: column %d dark %.4f, its neighbours at most %.4f\n", x, col[x] / H, near / H; bad++ }
        y = b * th - 1 + e; near = 0
        for (d = 3; d <= 4; d++) { near = row[y - d] > near ? row[y - d] : near; near = row[y + d] > near ? row[y + d] : near }
        if (row[y] / W > 1.5 * near / W + 0.01) { printf "seam: row %d dark %.4f, its neighbours at most %.4f\n", y, row[y] / W, near / W; bad++ }
      }
      for (b = 1; b < F; b++) {
        x = b * tw; y = b * th; nc = 0; nr = 0
        for (d = 2; d <= 4; d++) { nc = cj[x - d] > nc ? cj[x - d] : nc; nc = cj[x + d] > nc ? cj[x + d] : nc
                                   nr = rj[y - d] > nr ? rj[y - d] : nr; nr = rj[y + d] > nr ? rj[y + d] : nr }
        printf "tile border x %d: %d hard jumps (neighbours at most %d); y %d: %d (%d)\n", x, cj[x], nc, y, rj[y], nr
        if (cj[x] > 1.5 * nc + 10) { print "seam: marks cut at column " x; bad++ }
        if (rj[y] > 1.5 * nr + 10) { print "seam: marks cut at row " y; bad++ }
      }
      ratio = (dark / n) / (sd / sn)
      printf "tile borders checked: %d; ink %.4f of the snapshot, %.4f of the frame on screen (%.2fx)\n", 4 * (F - 1), dark / n, sd / sn, ratio
      if (ratio < 0.6 || ratio > 1.6) { print "the snapshot is not the view at a higher resolution (ink share)"; bad++ }
      exit bad ? 1 : 0 }' "$T/lion-npr.pgm" "$T/snapshot.pgm" || fail "snapshot seams / ink (see above)"
  ;;

*) die "unknown test '$TEST'" ;;
esac

if ((FAILS > 0)); then
  echo "[$TEST] $FAILS check(s) failed (work folder $T)"
  exit 1
fi
log "OK"
