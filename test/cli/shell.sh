#!/bin/bash
# dcshell check / volume-loss / shell from the command line: exit codes, one-line errors naming
# the file, atomic output, byte-identical reruns, and the written files certifying on their own.
set -u
BIN=$1; SRC=$2; SHARED=$3
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

# shell on every bundled example: certified, and the files as written pass `check`.
for ex in three_boxes nested split_cube snowman.obj bars/bars_30 plank_star; do
  "$BIN" shell -q --out "$T/o" "$SRC/data/$ex" || fail "shell $ex exit $?"
  "$BIN" check -q "$T"/o/shell_*.obj > /dev/null || fail "check of written shells of $ex"
  grep -q '"certified": true' "$T/o/report.json" || fail "report of $ex not certified"
  rm -rf "$T/o"
done

# Byte-identical reruns (timings left out of the report).
for m in lsf svm exact full; do
  "$BIN" shell -q --no-timings --method $m --out "$T/a" "$SRC/data/snowman.obj" || fail "run a $m"
  "$BIN" shell -q --no-timings --method $m --out "$T/b" "$SRC/data/snowman.obj" || fail "run b $m"
  diff -r "$T/a" "$T/b" > /dev/null || fail "method $m not deterministic"
  rm -rf "$T/a" "$T/b"
done
# The plank star runs full's three sweep starts on two threads: still the same bytes.
"$BIN" shell -q --no-timings --out "$T/a" "$SRC/data/plank_star" || fail "run a plank_star"
"$BIN" shell -q --no-timings --out "$T/b" "$SRC/data/plank_star" || fail "run b plank_star"
diff -r "$T/a" "$T/b" > /dev/null || fail "three starts not deterministic"
grep -q '"sweep_refits": [1-9]' "$T/a/report.json" || fail "plank star: no later start won"
grep -q '"sweep_start": "constructive"' "$T/a/report.json" || fail "plank star: $(grep sweep_start "$T/a/report.json")"
rm -rf "$T/a" "$T/b"
"$BIN" shell -q --starts 4 --out "$T/a" "$SRC/data/plank_star" 2> "$T/err"; [ $? -eq 2 ] || fail "--starts 4 accepted"
grep -q -- "--starts must be 1, 2 or 3" "$T/err" && [ ! -e "$T/a" ] || fail "--starts 4: $(cat "$T/err")"
"$BIN" shell -q --no-timings --starts 2 --out "$T/a" "$SRC/data/plank_star" || fail "--starts 2"
grep -q '"sweep_start": "refit-reshaped"' "$T/a/report.json" || fail "--starts 2: $(grep sweep_start "$T/a/report.json")"
rm -rf "$T/a"

# Existing non-empty output is refused without --force; an input is never overwritten.
mkdir -p "$T/busy"; echo x > "$T/busy/keep"
"$BIN" shell -q --out "$T/busy" "$SRC/data/three_boxes" 2> "$T/err"; [ $? -eq 2 ] || fail "non-empty out dir accepted"
[ "$(cat "$T/busy/keep")" = x ] || fail "out dir modified"
cp -r "$SRC/data/three_boxes" "$T/in"
"$BIN" shell -q --force --out "$T/in" "$T/in" 2> "$T/err"; [ $? -eq 2 ] || fail "input dir overwritten"
[ -f "$T/in/box_a.obj" ] || fail "input lost"

# Bad input: one line naming the file, exit 2, nothing written.
printf 'v 0 0 0\nv 1 0 nan\n' > "$T/bad.obj"
"$BIN" shell -q --out "$T/never" "$T/bad.obj" 2> "$T/err"; rc=$?
[ $rc -eq 2 ] || fail "bad input exit $rc"
[ "$(wc -l < "$T/err")" -eq 1 ] || fail "error is not one line: $(cat "$T/err")"
grep -q "bad.obj:2" "$T/err" || fail "error does not name file and line: $(cat "$T/err")"
[ ! -e "$T/never" ] || fail "output written for bad input"
ls -a "$T" | grep -q '^\.never' && fail "temporary directory left behind"
"$BIN" check "$T/missing.obj" 2> "$T/err"; [ $? -eq 2 ] || fail "missing file exit"
grep -q "missing.obj" "$T/err" || fail "missing file not named"
: > "$T/empty.obj"
"$BIN" volume-loss --parts "$T/empty.obj" --shells "$T/empty.obj" 2> "$T/err"; [ $? -eq 2 ] || fail "empty file exit"
grep -q "empty.obj: empty file" "$T/err" || fail "empty file message: $(cat "$T/err")"

# check: cubes sharing a face are certified (0), overlapping ones are not (1).
cube() { printf 'v %s 0 0\nv %s 0 0\nv %s 1 0\nv %s 1 0\nv %s 0 1\nv %s 0 1\nv %s 1 1\nv %s 1 1\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n' $1 $2 $2 $1 $1 $2 $2 $1; }
cube 0 1 > "$T/c0.obj"; cube 1 2 > "$T/c1.obj"; cube 0.5 1.5 > "$T/c2.obj"
"$BIN" check -q "$T/c0.obj" "$T/c1.obj" > /dev/null || fail "face-sharing cubes not certified"
"$BIN" check -q "$T/c0.obj" "$T/c2.obj" > "$T/rep.json"; [ $? -eq 1 ] || fail "overlapping cubes certified"
grep -q '"volume": 0.5' "$T/rep.json" || fail "overlap volume not 0.5"

# One file holding two cubes (no groups): two shells, as `shell` reads it as two parts.
{ cat "$T/c0.obj"; cube 1 2 | awk '/^f/ { printf "f"; for (i = 2; i <= NF; i++) printf " %d", $i + 8; print ""; next } { print }'; } > "$T/two.obj"
"$BIN" check -q "$T/two.obj" > "$T/two.json" || fail "two-component file not certified as two shells"
grep -q 'two.obj#1' "$T/two.json" || fail "second component not named"

# check -o never overwrites an input nor drops a mesh into an input directory; output errors are
# exit 2 with the reason, before any work.
mkdir -p "$T/in" && cp "$T/c0.obj" "$T/c1.obj" "$T/in/"
before=$(md5sum "$T/in/c0.obj")
"$BIN" check -q -o "$T/in/c0.obj" "$T/in" > /dev/null 2> "$T/err"; [ $? -eq 2 ] || fail "check -o onto an input: exit"
[ "$(md5sum "$T/in/c0.obj")" = "$before" ] || fail "check -o overwrote an input"
"$BIN" check -q -o "$T/in/report.obj" "$T/in" > /dev/null 2> "$T/err"; [ $? -eq 2 ] || fail "check -o into input dir"
[ ! -e "$T/in/report.obj" ] || fail "check -o wrote a mesh into the input directory"
"$BIN" check -q -o "$T/nodir/r.json" "$T/in" > /dev/null 2> "$T/err"; [ $? -eq 2 ] || fail "check -o missing dir: exit"
grep -q "nodir.*does not exist" "$T/err" || fail "check -o missing dir message: $(cat "$T/err")"
# A model too small for double volumes is refused, not a crash.
printf 'v 0 0 0\nv 1e-170 0 0\nv 0 1e-170 0\nv 0 0 1e-170\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' > "$T/tiny.obj"
"$BIN" check -q "$T/tiny.obj" > /dev/null 2> "$T/err"; [ $? -eq 2 ] || fail "tiny model: exit"
grep -q "tiny.obj: model is too small" "$T/err" || fail "tiny model message: $(cat "$T/err")"
# A flat closed mesh is called flat, not inward.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0.25 0.25 0\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' > "$T/flat.obj"
"$BIN" check "$T/flat.obj" > /dev/null 2> "$T/err"; [ $? -eq 1 ] || fail "flat mesh certified"
grep -q "flat.obj: flat: encloses no volume" "$T/err" || fail "flat mesh message: $(cat "$T/err")"

# volume-loss of shells against their parts.
"$BIN" shell -q --out "$T/s" "$SRC/data/three_boxes" || fail "shell three_boxes"
"$BIN" volume-loss -q --parts "$SRC/data/three_boxes" --shells "$T/s" > "$T/vl.json" || fail "volume-loss exit"
grep -q '"union_volume": 4.96875' "$T/vl.json" || fail "union volume of three boxes: $(grep union_volume "$T/vl.json")"

# Sixteen planks through one axis (65,535 overlapping subsets): the union switches to the convex
# decomposition, and the whole pipeline finishes and certifies.
mkdir -p "$T/star"
for k in $(seq 0 15); do
  awk -v k=$k 'BEGIN { a = 3.14159265358979 * k / 16; c = cos(a); s = sin(a)
    for (i = 0; i < 8; i++) { x = (i % 2) ? 4 : -4; y = (int(i / 2) % 2) ? 0.3 : -0.3; z = (i >= 4) ? 0.05 : -0.05
      printf "v %.12f %.12f %.12f\n", c * x - s * y, s * x + c * y, z + 0.005 * k }
    print "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 2 4 8 6\nf 4 3 7 8\nf 3 1 5 7" }' > "$T/star/plank_$k.obj"
done
"$BIN" shell -q --out "$T/star_out" "$T/star" || fail "shell of the plank star"
grep -q '"certified": true' "$T/star_out/report.json" || fail "plank star shells not certified"
[ "$(ls "$T/star_out"/shell_*.obj | wc -l)" -eq 16 ] || fail "plank star: a plank lost its shell"
"$BIN" volume-loss -q --parts "$T/star" --shells "$T/star_out" > "$T/star.json" || fail "volume-loss of the plank star"
grep -q '"union_method": "decomposition"' "$T/star.json" || fail "plank star union: $(grep union_ "$T/star.json")"
# Both are certified enclosures of the same exact number (the two reached it by different walks).
# The value after the key (the key's own letters must not be taken into the number).
value() { grep -h "\"$1\":" "$2" | head -1 | sed 's/.*": *//; s/[,} ]*$//'; }
u1=$(value union_volume "$T/star.json"); u2=$(value union_volume "$T/star_out/report.json")
awk -v a="$u1" -v b="$u2" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(a > 0 && d <= 1e-12 * a) }' ||
  fail "the shell report and volume-loss disagree on the union: $u1 vs $u2"

# Shared data: the paper's own shells are refused, naming pairs.
if [ -d "$SHARED/paper-output" ]; then
  for d in "$SHARED"/paper-output/*/; do
    "$BIN" check -q "$d" > "$T/p.json"; [ $? -eq 1 ] || fail "paper output $d certified"
    grep -q '"ratio_to_smaller"' "$T/p.json" || fail "no overlapping pair named for $d"
  done
fi
echo "ok"
