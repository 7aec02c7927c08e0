#!/bin/bash
# End-to-end test of `dcshell unfold`: outputs, exit codes, one-line errors, atomic output,
# reproducibility. Usage: bash unfold.sh <dcshell> <source-dir> <shared-data-dir>
set -u
BIN=$1
DATA=${3:-}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

# A unit cube as 12 triangles, a tetrahedron, an open box, a dented (non-convex) cube.
cat > "$T/cube.obj" <<'OBJ'
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 4 3
f 1 3 2
f 5 6 7
f 5 7 8
f 1 2 6
f 1 6 5
f 2 3 7
f 2 7 6
f 3 4 8
f 3 8 7
f 4 1 5
f 4 5 8
OBJ
cat > "$T/tet.obj" <<'OBJ'
v 1 1 1
v 1 -1 -1
v -1 1 -1
v -1 -1 1
f 1 2 3
f 1 4 2
f 1 3 4
f 2 4 3
OBJ
head -n 18 "$T/cube.obj" > "$T/open.obj"
sed 's/^v 1 1 1$/v 0.6 0.6 0.6/' "$T/cube.obj" > "$T/dent.obj"

"$BIN" unfold --help > "$T/help.txt" || fail "--help exit code"
grep -q -- "--heuristic" "$T/help.txt" || fail "--help lists options"

"$BIN" unfold --out "$T/out" "$T/cube.obj" "$T/tet.obj" 2> "$T/err.txt" || fail "unfold of two convex shells: exit $? ($(cat "$T/err.txt"))"
for f in net_000.obj net_001.obj nets.svg unfold.json; do [ -s "$T/out/$f" ] || fail "missing $f"; done
[ "$(grep -c '^f ' "$T/out/net_000.obj")" = 12 ] || fail "net_000.obj has not 12 faces"
[ "$(grep -c '^v ' "$T/out/net_000.obj")" = 14 ] || fail "cube net should have 14 net vertices (7 cut edges)"
grep '^v ' "$T/out/net_000.obj" | awk '$4 != 0 { exit 1 }' || fail "net not flat"
grep -q '"overlap_free": true' "$T/out/unfold.json" || fail "json overlap_free"
grep -q '"fold_path_verified": true' "$T/out/unfold.json" || fail "json fold_path_verified"
grep -q '"fold_fallback": false' "$T/out/unfold.json" || fail "json fold_fallback (the cube's best net folds)"
grep -q '"cut_length": 7[,.]' "$T/out/unfold.json" || grep -q '"cut_length": 7$' "$T/out/unfold.json" || fail "cube cut length 7"

# Reproducible: same bytes for the same seed.
"$BIN" unfold --out "$T/out2" "$T/cube.obj" "$T/tet.obj" 2> /dev/null || fail "second run"
cmp -s "$T/out/net_000.obj" "$T/out2/net_000.obj" || fail "net_000.obj differs between runs"
cmp -s "$T/out/nets.svg" "$T/out2/nets.svg" || fail "nets.svg differs between runs"
"$BIN" unfold --no-timings --out "$T/nt1" "$T/cube.obj" "$T/tet.obj" 2> /dev/null || fail "--no-timings run"
"$BIN" unfold --no-timings --out "$T/nt2" "$T/cube.obj" "$T/tet.obj" 2> /dev/null || fail "--no-timings run 2"
diff -r "$T/nt1" "$T/nt2" > /dev/null || fail "--no-timings outputs differ between runs"

# Every heuristic, PDF sheets, motion frames.
for h in steepest flat min-perimeter random ga; do
  "$BIN" unfold --heuristic $h --objective cut-length --format pdf --paper letter --out "$T/h_$h" "$T/cube.obj" 2> /dev/null \
    || fail "heuristic $h"
  [ -s "$T/h_$h/nets.pdf" ] || fail "heuristic $h: no nets.pdf"
done
"$BIN" unfold --motion "$T/motion.obj" --motion-frames 5 --out "$T/mo" "$T/tet.obj" 2> /dev/null || fail "--motion"
for i in 000 001 002 003 004; do [ -s "$T/motion_$i.obj" ] || fail "missing motion frame $i"; done
[ ! -e "$T/motion_005.obj" ] || fail "too many motion frames"

# Motion frames are never overwritten without --force, and may not live inside --out.
"$BIN" unfold --motion "$T/motion.obj" --motion-frames 5 --out "$T/mo2" "$T/tet.obj" 2> "$T/err.txt"
[ $? = 2 ] || fail "--motion over existing frames without --force"
[ ! -e "$T/mo2" ] || fail "--motion refusal left an output directory"
"$BIN" unfold --motion "$T/mo3/m.obj" --out "$T/mo3" "$T/tet.obj" 2> /dev/null; [ $? = 2 ] || fail "--motion inside --out"
# A flat shell among good ones is skipped with a warning; net_k keeps the input index.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0.25 0.25 0\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' > "$T/a_flat.obj"
"$BIN" unfold --out "$T/fl" "$T/a_flat.obj" "$T/tet.obj" 2> "$T/err.txt" || fail "flat shell among good ones: $(cat "$T/err.txt")"
grep -q "a_flat.obj is flat.*skipped" "$T/err.txt" || fail "flat shell warning: $(cat "$T/err.txt")"
[ -s "$T/fl/net_001.obj" ] && [ ! -e "$T/fl/net_000.obj" ] || fail "flat shell: net numbering"
# -q: the same outputs, nothing on stderr (the warning is in unfold.json only).
"$BIN" unfold -q --no-timings --out "$T/flq" "$T/a_flat.obj" "$T/tet.obj" 2> "$T/err.txt" || fail "quiet run"
[ ! -s "$T/err.txt" ] || fail "-q still printed: $(cat "$T/err.txt")"
[ -s "$T/flq/net_001.obj" ] || fail "-q wrote no net"

# A file of several objects (the shells.obj that `shell` writes, a V-HACD output) is a set of
# shells, as for check and remesh: one net per object, named by it, the same as from the files.
{ echo "o first"; cat "$T/cube.obj"; echo "o second"; sed -n '1,4p' "$T/tet.obj";
  sed -n '5,$p' "$T/tet.obj" | awk '{ print "f", $2 + 8, $3 + 8, $4 + 8 }'; } > "$T/both.obj"
"$BIN" unfold -q --no-timings --out "$T/obj2" "$T/both.obj" || fail "two objects in one file: exit $?"
for k in 000 001; do  # the same net; only the header's name differs
  diff -q <(sed 1d "$T/obj2/net_$k.obj") <(sed 1d "$T/nt1/net_$k.obj") > /dev/null || fail "object net $k differs from its file's"
done
grep -q '^# dcshell net second:' "$T/obj2/net_001.obj" || fail "object net header does not name the object"
grep -q '"input": ".*both.obj#second"' "$T/obj2/unfold.json" || fail "object input not named"
grep -q '"name": "second"' "$T/obj2/unfold.json" || fail "object net not named by its object"
grep -v '^o ' "$T/both.obj" > "$T/both_nogroups.obj"
"$BIN" unfold -q --out "$T/cc2" "$T/both_nogroups.obj" || fail "two components in one file: exit $?"
[ -s "$T/cc2/net_001.obj" ] || fail "two components: no second net"
grep -q '"name": "both_nogroups_1"' "$T/cc2/unfold.json" || fail "component net not named by its file and number"

# Bad input: one line naming the file, exit 2, nothing written.
expect_2() {
  local what=$1; shift
  "$BIN" unfold "$@" > /dev/null 2> "$T/err.txt"
  local rc=$?
  [ $rc = 2 ] || fail "$what: exit $rc, expected 2"
  [ "$(wc -l < "$T/err.txt")" = 1 ] || fail "$what: expected one error line, got: $(cat "$T/err.txt")"
}
expect_2 "open mesh" --out "$T/bad1" "$T/open.obj"
grep -q "open.obj" "$T/err.txt" || fail "open mesh error does not name the file"
[ ! -e "$T/bad1" ] || fail "output written for bad input"
expect_2 "missing file" --out "$T/bad2" "$T/nope.obj"
[ ! -e "$T/bad2" ] || fail "output written for a missing file"
expect_2 "bad heuristic" --heuristic best-ever --out "$T/bad3" "$T/cube.obj"
expect_2 "bad paper" --paper a9000 --out "$T/bad4" "$T/cube.obj"
expect_2 "no --out" "$T/cube.obj"
expect_2 "negative fallback slack" --fold-fallback-slack -1 --out "$T/bad5" "$T/cube.obj"
grep -q -- "--fold-fallback-slack" "$T/err.txt" || fail "fallback slack error does not name the option"
[ ! -e "$T/bad5" ] || fail "output written for a bad option"
expect_2 "existing output" --out "$T/out" "$T/cube.obj"
[ -s "$T/out/net_001.obj" ] || fail "existing output touched"
expect_2 "output over an input" --force --out "$T" "$T/cube.obj"

# Non-convex: a clear message, an attempt anyway.
"$BIN" unfold --out "$T/dent" "$T/dent.obj" > /dev/null 2> "$T/err.txt"
grep -q "not convex" "$T/err.txt" || fail "no message for a non-convex mesh"
[ -s "$T/dent/net_000.obj" ] || fail "no attempt on the non-convex mesh"

# Shared data (optional): the cube models give 7 cube edges of cuts.
if [ -d "$DATA/convex" ]; then
  "$BIN" unfold --objective cut-length --out "$T/c10" "$DATA/convex/cube-10.obj" 2> /dev/null || fail "cube-10"
  grep -q '"cut_length": 70' "$T/c10/unfold.json" || fail "cube-10 cut length should be 70"
fi
echo "ok"
