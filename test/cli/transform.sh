#!/bin/bash
# The same job at any scale and place: bundled examples scaled by 1e-4 and 1e5, moved 1e5 away
# and rotated still give certified shells whose volume loss matches the original's, and the paper
# pipeline (remeshing) and the unfolder succeed on them. Tolerances, margins and flatness tests
# are relative; a slip to an absolute one shows up here first.
# Usage: bash transform.sh <dcshell> <source-dir> [<shared-data-dir>]
set -u
BIN=$1; SRC=$2
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

# transform DIR_IN DIR_OUT SCALE TX TY TZ DEGREES: rotate about z by DEGREES and about x by 0.37
# of it, scale, then translate (every 'v' line; faces and groups are kept).
transform() {
  mkdir -p "$2"
  for f in "$1"/*.obj; do
    awk -v s="$3" -v tx="$4" -v ty="$5" -v tz="$6" -v deg="$7" '
      BEGIN { a = deg * 3.14159265358979 / 180; b = 0.37 * a; ca = cos(a); sa = sin(a); cb = cos(b); sb = sin(b) }
      /^v / { x = ca * $2 - sa * $3; y = sa * $2 + ca * $3; z = $4
              y2 = cb * y - sb * z; z2 = sb * y + cb * z
              printf "v %.17g %.17g %.17g\n", s * x + tx, s * y2 + ty, s * z2 + tz; next }
      { print }' "$f" > "$2/$(basename "$f")"
  done
}
# The report's first volume_loss (the whole set's), the number after the key.
loss() { grep -h '"volume_loss":' "$1/report.json" | head -1 | sed 's/.*": *//; s/[,} ]*$//'; }

for ex in bars/bars_30 three_boxes; do
  name=$(basename "$ex")
  "$BIN" shell -q --out "$T/$name-ref" "$SRC/data/$ex" || fail "shell $ex"
  ref=$(loss "$T/$name-ref")
  for t in "tiny 1e-4 0 0 0 0" "far 1 1e5 -2e5 3e5 0" "big 1e5 0 0 0 17" "turned 1 0.5 0.25 -1 33"; do
    set -- $t
    transform "$SRC/data/$ex" "$T/$name-$1" "$2" "$3" "$4" "$5" "$6"
    "$BIN" shell -q --out "$T/$name-$1-out" "$T/$name-$1" || fail "shell $ex $1: exit $?"
    "$BIN" check -q "$T/$name-$1-out"/shell_*.obj > /dev/null || fail "check of $ex $1"
    # Moving 1e5 away leaves the coordinates 1e5 times fewer digits: the cut planes land a few
    # rounding units elsewhere, so the loss is compared to 1e-4 of itself (measured: 3e-8 on the
    # bars, 5e-6 on the boxes).
    l=$(loss "$T/$name-$1-out")
    awk -v a="$ref" -v b="$l" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(a > 0 && d <= 1e-4 * a) }' ||
      fail "$ex $1: volume loss $l, untransformed $ref"
    "$BIN" shell -q --simplify-iterations 10 --out "$T/$name-$1-paper" "$T/$name-$1" || fail "paper pipeline $ex $1: exit $?"
    "$BIN" check -q "$T/$name-$1-paper"/shell_*.obj > /dev/null || fail "check of the paper pipeline's $ex $1"
    grep -q '"fatness_after"' "$T/$name-$1-paper/report.json" || fail "$ex $1: no remesh report"
    # Every net one piece, overlap-free and its folding verified (exit 0).
    "$BIN" unfold -q --out "$T/$name-$1-nets" "$T/$name-$1-paper"/shell_*.obj || fail "unfold of $ex $1: exit $?"
  done
done
echo "ok"
