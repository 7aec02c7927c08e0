#!/usr/bin/env bash
# End-to-end test of `dcshell remesh`: exit codes, certified output, report fields, atomic output.
# Usage: bash remesh.sh <dcshell-binary> <source-dir> <shared-data-dir>
set -u
bin=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

# Two convex shells sharing the face x = 0 exactly: a drum (two half circles of 25 points at
# z = 0 and z = 2) split in half; its sides are needles worth regularising.
awk -v dir="$tmp" '
BEGIN {
  pi = atan2(0, -1); n = 24
  for (s = 0; s < 2; s++) {
    f = dir (s ? "/right.obj" : "/left.obj"); sg = s ? -1 : 1
    # half circle x <= 0 (left) or x >= 0 (right): i = 0..n, bottom then top
    for (i = 0; i <= n; i++) {
      t = pi / 2 + pi * i / n; x = cos(t); y = sin(t); if (i == 0 || i == n) x = 0
      printf "v %.17g %.17g 0\n", sg * x, y > f
    }
    for (i = 0; i <= n; i++) {
      t = pi / 2 + pi * i / n; x = cos(t); y = sin(t); if (i == 0 || i == n) x = 0
      printf "v %.17g %.17g 2\n", sg * x, y > f
    }
    # bottom (outward -z), top (+z), sides, flat x = 0 face; reversed for the mirrored half
    bot = ""; top = ""
    for (i = 0; i <= n; i++) { bot = bot " " (n + 1 - i); top = top " " (n + 2 + i) }
    if (s) { tmp = ""; for (i = 0; i <= n; i++) tmp = tmp " " (i + 1); bot = tmp; tmp = ""; for (i = 0; i <= n; i++) tmp = tmp " " (2 * n + 2 - i); top = tmp }
    print "f" bot > f; print "f" top > f
    for (i = 1; i <= n; i++) {
      a = i; b = i + 1; c = n + 1 + i + 1; d = n + 1 + i
      if (s) printf "f %d %d %d %d\n", a, d, c, b > f; else printf "f %d %d %d %d\n", a, b, c, d > f
    }
    if (s) printf "f %d %d %d %d\n", 1, n + 1, 2 * n + 2, n + 2 > f; else printf "f %d %d %d %d\n", 1, n + 2, 2 * n + 2, n + 1 > f
  }
}
'
"$bin" check -q "$tmp/left.obj" "$tmp/right.obj" > /dev/null || fail "test input is not a certified pair"

"$bin" remesh --help > /dev/null || fail "--help"
"$bin" remesh --out "$tmp/out" "$tmp/left.obj" "$tmp/right.obj" 2> "$tmp/err"
[ $? -eq 0 ] || { cat "$tmp/err"; fail "remesh of a certified pair"; }
[ -f "$tmp/out/shell_000.obj" ] && [ -f "$tmp/out/shell_001.obj" ] && [ -f "$tmp/out/report.json" ] || fail "outputs"
"$bin" check -q "$tmp/out/shell_000.obj" "$tmp/out/shell_001.obj" > /dev/null || fail "written shells are not certified"
"$bin" remesh -q --out "$tmp/outq" "$tmp/left.obj" "$tmp/right.obj" 2> "$tmp/errq" || fail "quiet remesh"
[ ! -s "$tmp/errq" ] && [ -f "$tmp/outq/report.json" ] || fail "-q: $(cat "$tmp/errq")"
for k in faces_before faces_after fatness_before fatness_after volume_increase domed_facets max_sink; do
  grep -q "\"$k\"" "$tmp/out/report.json" || fail "report lacks $k"
done
# Fatter, not bigger than allowed, never more faces.
awk -F'[:,]' '/"faces_before"/ {fb=$2} /"faces_after"/ {if ($2 > fb) bad=1}
  /"fatness_before"/ {b=$2} /"fatness_after"/ {if ($2 <= b) bad=1}
  /"volume_increase"/ {if ($2 > 0.05 + 1e-9) bad=1}
  /"domed_facets"/ {domed += $2} /"max_sink"/ {if ($2 > 1e-7) bad=1}
  END {if (domed == 0) bad=1; exit bad}' "$tmp/out/report.json" || fail "report numbers"
# The flat caps and the shared face were domed above; without domes nothing is, nothing sinks.
"$bin" remesh --no-domes --out "$tmp/nd" "$tmp/left.obj" "$tmp/right.obj" 2> /dev/null || fail "--no-domes"
awk -F'[:,]' '/"max_sink"/ {if ($2 != 0) bad=1} /"domed_facets"/ {if ($2 != 0) bad=1} END {exit bad}' \
  "$tmp/nd/report.json" || fail "--no-domes still domed"
# Without splits none is made (the report counts them).
"$bin" remesh --no-splits --out "$tmp/ns" "$tmp/left.obj" "$tmp/right.obj" 2> /dev/null || fail "--no-splits"
awk -F'[:,]' '/"splits"/ {n++; if ($2 != 0) bad=1} END {if (n != 2) bad=1; exit bad}' "$tmp/ns/report.json" ||
  fail "--no-splits still split"
# Without flips none is made either (the default run above made some: the check can fail).
awk -F'[:,]' '/"flips"/ {n += $2} END {exit !(n > 0)}' "$tmp/out/report.json" || fail "no flips by default"
"$bin" remesh --no-flips --out "$tmp/nf" "$tmp/left.obj" "$tmp/right.obj" 2> /dev/null || fail "--no-flips"
awk -F'[:,]' '/"flips"/ {n++; if ($2 != 0) bad=1} END {if (n != 2) bad=1; exit bad}' "$tmp/nf/report.json" ||
  fail "--no-flips still flipped"

# Refuses an existing output, bad options and bad input: exit 2, nothing written.
"$bin" remesh --out "$tmp/out" "$tmp/left.obj" 2> /dev/null; [ $? -eq 2 ] || fail "existing output dir"
"$bin" remesh --max-volume-increase -1 --out "$tmp/o2" "$tmp/left.obj" 2> /dev/null; [ $? -eq 2 ] || fail "negative ratio"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' > "$tmp/open.obj"
"$bin" remesh --out "$tmp/o3" "$tmp/open.obj" 2> "$tmp/err"; [ $? -eq 2 ] || fail "open mesh accepted"
grep -q "open.obj" "$tmp/err" || fail "error does not name the file"
[ $(wc -l < "$tmp/err") -eq 1 ] || fail "error is not one line"
# Overlapping shells are bad input.
"$bin" remesh --out "$tmp/o4" "$tmp/left.obj" "$tmp/left.obj" 2> /dev/null; [ $? -eq 2 ] || fail "overlapping inputs accepted"
[ ! -e "$tmp/o2" ] && [ ! -e "$tmp/o3" ] && [ ! -e "$tmp/o4" ] || fail "something written on error"

# Shared data (optional): the paper's own shells are not exactly disjoint, so they are refused.
if [ -d "${3:-}/paper-output" ]; then
  d=$(ls -d "$3"/paper-output/*i0* 2>/dev/null | head -1)
  if [ -n "$d" ]; then
    "$bin" remesh --out "$tmp/o5" "$d" 2> /dev/null; [ $? -eq 2 ] || fail "overlapping paper shells accepted"
  fi
fi
echo "ok"
