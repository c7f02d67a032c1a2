# Shared by tests/cli_*.sh scripts that source it (not a test itself): check (counts failures in
# $fail) and a sampled unit cube as ascii PLY.
fail=0
# built_with_render BIN: whether BIN has the renderer (without it, `render` says "no renderer";
# the commands that need no GL, e.g. lines --svg, work in both builds)
built_with_render() { case "$("$1" render --help 2>&1)" in *"no renderer"*) return 1 ;; esac; return 0; }
check() { if ! eval "$1"; then echo "FAILED: $2" >&2; fail=1; fi; }
# cube_ply FILE: the surface of the unit cube sampled every 0.1 (602 points, float x y z)
cube_ply() {
  awk 'BEGIN { m = 10; h = 0.1; n = 0
    for (i = 0; i <= m; i++) for (j = 0; j <= m; j++) for (k = 0; k <= m; k++) {
      if (i > 0 && i < m && j > 0 && j < m && k > 0 && k < m) continue
      l[n++] = sprintf("%g %g %g", i * h, j * h, k * h) }
    print "ply\nformat ascii 1.0\nelement vertex " n "\nproperty float x\nproperty float y\nproperty float z\nend_header"
    for (q = 0; q < n; q++) print l[q] }' > "$1"
}
