#!/bin/bash
# `pointnpr bench quality` runs end to end on the small scene: every style's image of the scene and
# of the ball alone, the truth overlay and the line checks, figures.md with one row per style and
# the acceptance table, the same table on stdout; the sparse preset runs and judges only the
# figures asked at any density; bad options are usage errors. It does not judge the figures (that
# is quality_acceptance.sh, behind -DPNPR_QUALITY_GATE=ON). Exit 77 (skipped) without headless GL.
# usage: cli_bench_quality.sh POINTNPR SCRATCH_DIR
set -u
cli=$1
out=$2/bench-quality
rm -rf "$out"
fail() { echo "FAIL: $*" >&2; exit 1; }

"$cli" bench quality -o "$out" > "$out.stdout" 2> "$out.stderr"
rc=$?
if [ $rc -eq 77 ]; then cat "$out.stderr" >&2; exit 77; fi
[ $rc -eq 0 ] || { cat "$out.stderr" >&2; fail "bench quality exited $rc"; }
for style in points lines cartoon sketchy stipple; do
  for what in scene ball; do
    [ -s "$out/$what-$style.png" ] || fail "missing $out/$what-$style.png"
  done
  grep -q "^| $style | [0-9]" "$out/figures.md" || fail "no row for $style in figures.md"
done
[ -s "$out/scene-truth.png" ] || fail "missing the truth overlay"
for what in scene ball; do
  [ -s "$out/$what-lines-check.png" ] || fail "missing $out/$what-lines-check.png"
done
grep -q "^Scene: small, [0-9]* points" "$out/figures.md" || fail "no scene line in figures.md"
! grep -q "not judged" "$out/figures.md" || fail "the small scene leaves a figure unjudged"
grep -q "^| lines: visible crease edges inked within 2 px | [0-9.]* | >= 0.80 |" "$out/figures.md" ||
  fail "no acceptance table in figures.md"
[ "$(grep -c '^| ' "$out.stdout")" -eq "$(grep -c '^| ' "$out/figures.md")" ] || fail "stdout and figures.md differ"

"$cli" bench quality --sparse -o "$out-sparse" > "$out-sparse.stdout" 2> "$out-sparse.stderr" ||
  { cat "$out-sparse.stderr" >&2; fail "bench quality --sparse failed"; }
grep -q "^Scene: sparse, [0-9]* points" "$out-sparse.stdout" || fail "no sparse scene line"
grep -q "^| cartoon: outline ink / drawn pixels | [0-9.]* | <= 0.15 | \(pass\|\*\*miss\*\*\) |" "$out-sparse.stdout" ||
  fail "the sparse scene does not judge the cartoon's outline ink"
grep -q "^| cartoon: speckle | [0-9.]* | <= 0.02 | (not judged when sparse) |" "$out-sparse.stdout" ||
  fail "the sparse scene judges a figure asked of the small scene only"

"$cli" bench quality --full --sparse > /dev/null 2>&1
[ $? -eq 2 ] || fail "--full with --sparse is not a usage error"
"$cli" bench quality --bogus > /dev/null 2>&1
[ $? -eq 2 ] || fail "an unknown option is not a usage error"
"$cli" bench quality --help | grep -q -- "--sparse" || fail "no help"
echo "cli_bench_quality: ok"
