#!/bin/sh
# `seislide run` output hygiene and bad input (issue 15): unique floor ids,
# a fresh folder swapped in (no stale files), the output folder checked
# before any work, umask permissions, implausible ZPA refused without
# --force, absurd values refused with file:line:value, interrupted runs
# leave nothing behind, --created 0 reproducible.
. "$(dirname "$0")/lib.sh"
t_suite cli_deliver
D=$T_TMP
FAST="--sets 2 --mu 0.2,0.4 -q --created 1700000000"
mkdir -p "$D/fl" "$D/a" "$D/b"
cp floors/01-ground.ini "$D/fl/"
# no file left: neither the output folder nor a hidden temporary beside it
nothing_left() { # NAME DIR
  if [ ! -e "$2" ] && ! ls -a "$(dirname "$2")" | grep -q "^\.$(basename "$2")\.tmp-"; then t_pass; else t_fail "$1: output left behind: $(ls -a "$(dirname "$2")" | tr '\n' ' ')"; fi
}

# names differing only in punctuation: two floors, two files, two columns
sed 's/^name = .*/name = Aux bldg, el. 12 m/' floors/02-el12.ini > "$D/fl/aux-a.ini"
sed 's/^name = .*/name = Aux bldg; el. 12 m/' floors/02-el12.ini > "$D/fl/aux-b.ini"
t_run run "$D/fl" -o "$D/res" $FAST; t_expect_rc punct 0
[ -s "$D/res/floor_aux-a.csv" ] && [ -s "$D/res/floor_aux-b.csv" ] && t_pass || t_fail "per-floor CSVs: $(ls "$D/res")"
grep -v '^#' "$D/res/summary.csv" | head -1 | grep -q "^mu,01-ground_clearance_mm,aux-a_clearance_mm,aux-b_clearance_mm" && t_pass || t_fail "summary columns: $(grep -v '^#' "$D/res/summary.csv" | head -1)"
grep -q "^# floor: Aux bldg; el. 12 m" "$D/res/floor_aux-b.csv" && t_pass || t_fail "floor name in its CSV"
# the same file stem twice: refused before any work, nothing written
cp floors/02-el12.ini "$D/a/x.ini"; sed 's/^name = .*/name = Other/' floors/02-el12.ini > "$D/b/x.ini"
t_run run "$D/a/x.ini" "$D/b/x.ini" -o "$D/dup" $FAST; t_expect_rc dup-id 1
t_expect_err dup-id-msg "x.ini: floor id 'x'.*rename one file"; nothing_left dup-id "$D/dup"
# the same name twice (case aside): refused
sed 's/^name = .*/name = AUX BLDG, EL. 12 M/' floors/02-el12.ini > "$D/b/y.ini"
t_run run "$D/fl/aux-a.ini" "$D/b/y.ini" -o "$D/dupn" $FAST; t_expect_rc dup-name 1
t_expect_err dup-name-msg "floor name .* is also that of"; nothing_left dup-name "$D/dupn"
# a floor id that is another floor's name (without case): a components list's
# floor=Roof would name two floors; refused naming both files, nothing written
sed 's/^name = .*/name = Ground slab/' floors/02-el12.ini > "$D/a/roof.ini"
sed 's/^name = .*/name = Roof/' floors/04-roof36.ini > "$D/b/top.ini"
t_run run "$D/a/roof.ini" "$D/b/top.ini" -o "$D/dupr" $FAST; t_expect_rc id-name 1
t_expect_err id-name-msg "b/top.ini: floor name 'Roof' is the floor id of .*a/roof.ini"; nothing_left id-name "$D/dupr"
t_run run "$D/b/top.ini" "$D/a/roof.ini" -o "$D/dupr" $FAST; t_expect_rc name-id 1
t_expect_err name-id-msg "a/roof.ini: floor id 'roof' .* is the name of the floor of .*b/top.ini \('Roof'"
# ids compared without case
sed 's/^name = .*/name = Upper/' floors/02-el12.ini > "$D/b/ROOF.ini"
t_run run "$D/a/roof.ini" "$D/b/ROOF.ini" -o "$D/dupr" $FAST; t_expect_rc id-case 1
t_expect_err id-case-msg "ROOF.ini: floor id 'ROOF' .* is also that of .*a/roof.ini \(floor ids are compared without case\)"

# a second run with fewer floors: the old floor CSVs are gone
t_run run "$D/fl/01-ground.ini" -o "$D/res" $FAST; t_expect_rc fewer 0
[ ! -e "$D/res/floor_aux-a.csv" ] && [ -s "$D/res/floor_01-ground.csv" ] && t_pass || t_fail "stale files: $(ls "$D/res")"
ls -a "$D" | grep -q '\.tmp-' && t_fail "temporary folder left: $(ls -a "$D")" || t_pass

# the output folder is checked before any work
t_run run "$D/fl/01-ground.ini" -o README.md --sets 2 --mu 0.2; t_expect_rc out-file 1
t_expect_err out-file-msg "README.md: output path exists and is not a folder"
grep -q synthesis "$T_ERR" && t_fail "work done before the output check" || t_pass
mkdir -p "$D/mine" && echo keep > "$D/mine/notes.txt"
t_run run "$D/fl/01-ground.ini" -o "$D/mine" $FAST; t_expect_rc foreign 1
t_expect_err foreign-msg "mine: the output folder holds 'notes.txt' and seislide did not make it"
[ -s "$D/mine/notes.txt" ] && t_pass || t_fail "a foreign file was touched"
# missing parents are made (mkdir -p); a parent that is a file is an error naming it
t_run run "$D/fl/01-ground.ini" -o "$D/no/such/dir" $FAST; t_expect_rc no-parent 0
[ -f "$D/no/such/dir/summary.csv" ] && t_pass || t_fail "no-parent: no outputs in the made folder"
t_run run "$D/fl/01-ground.ini" -o "$D/mine/notes.txt/out" $FAST; t_expect_rc parent-file 1
t_expect_err parent-file-msg "mine/notes.txt: cannot create the output folder's parent: Not a directory"
# a trailing slash names the same folder, new or existing
t_run run "$D/fl/01-ground.ini" -o "$D/slash/" $FAST; t_expect_rc slash-new 0
t_run run "$D/fl/01-ground.ini" -o "$D/slash/" $FAST; t_expect_rc slash-again 0
[ -s "$D/slash/summary.csv" ] && t_pass || t_fail "trailing slash: $(ls -a "$D")"

# permissions follow the umask
(umask 022; "$SEISLIDE_BIN" run "$D/fl/01-ground.ini" -o "$D/u022" $FAST) && \
  [ "$(stat -c %a "$D/u022/summary.csv")" = 644 ] && [ "$(stat -c %a "$D/u022/seislide-clearance.xlsx")" = 644 ] && \
  [ "$(stat -c %a "$D/u022")" = 755 ] && t_pass || t_fail "umask 022: $(ls -la "$D/u022" | head -3)"
(umask 027; "$SEISLIDE_BIN" run "$D/fl/01-ground.ini" -o "$D/u027" $FAST) && \
  [ "$(stat -c %a "$D/u027/floors.csv")" = 640 ] && t_pass || t_fail "umask 027: $(ls -la "$D/u027" | head -3)"

# units = gal on values in g: ZPA 0.0003 g refused (file, line, value), or run with --force
sed 's/^units = g/units = gal/' floors/01-ground.ini > "$D/gal.ini"
L=$(grep -n '^units' "$D/gal.ini" | cut -d: -f1)
t_run run "$D/gal.ini" -o "$D/gal" $FAST; t_expect_rc gal 1
t_expect_err gal-msg "gal.ini:$L: units = gal gives a horizontal ZPA of 0.0003059 g, outside the plausible 0.01-5 g"
nothing_left gal "$D/gal"
t_run run "$D/gal.ini" -o "$D/galf" $FAST --force; t_expect_rc gal-force 0

# absurd floor values: file, line, value
awk '/^f_hz/ && !d { sub(/0\.1,/, "1e-300,"); d = 1 } { print }' floors/04-roof36.ini > "$D/f300.ini"
L=$(grep -n '1e-300' "$D/f300.ini" | cut -d: -f1)
t_run run "$D/f300.ini" -o "$D/f300" $FAST; t_expect_rc f-tiny 1
t_expect_err f-tiny-msg "f300.ini:$L: f_hz: frequency 1e-300 Hz outside"; nothing_left f-tiny "$D/f300"
awk '/^sa_0.1 / && !d { sub(/0\.0188,/, "1e308,"); d = 1 } { print }' floors/04-roof36.ini > "$D/big.ini"
L=$(grep -n '1e308' "$D/big.ini" | cut -d: -f1)
t_run asce --floor "$D/big.ini" --mu 0.1; t_expect_rc sa-huge 1
t_expect_err sa-huge-msg "big.ini:$L: sa_0.1: value 1e\+308 g is above 1000 g"
truncate -s 17M "$D/huge.ini"
t_run run "$D/huge.ini" -o "$D/huge" $FAST; t_expect_rc floor-size 1
t_expect_err floor-size-msg "huge.ini: file of 17825792 bytes is larger than the 16777216 bytes"

# absurd motion values: AT2 with 1e300 g, a two-column file, a 3 GB file (sparse: refused unread)
R=tests/data/motion
if ls $R/*.AT2 >/dev/null 2>&1; then
  A=$R/cms2.AT2
  awk 'NR == 5 { $2 = "1e300" } { print }' "$A" > "$D/bad.AT2"
  t_run slide --h1 "$D/bad.AT2" --mu 0.3; t_expect_rc at2-huge 1
  t_expect_err at2-huge-msg "bad.AT2:5: acceleration 1e\+300 cm/s2 is above 100 g"
else
  t_skip "no AT2 fixture in $R"
fi
printf 'time_s,acc_g\n0,0.1\n0.01,2e300\n0.02,0.1\n' > "$D/two.csv"
t_run slide --h1 "$D/two.csv" --mu 0.3; t_expect_rc csv-huge 1
t_expect_err csv-huge-msg "two.csv:3: acceleration 2e\+300 g is above 100 g"
printf "0.1\\n1e308\\n" > "$D/ovf.csv"
t_run slide --h1 "$D/ovf.csv" --dt 0.01 --units g --mu 0.3
[ "$T_RC" -ne 0 ] && grep -q "ovf.csv:2:" "$T_ERR" && t_pass || t_fail "overflow in SI: $(head -c 300 "$T_ERR")"
truncate -s 3G "$D/huge.AT2"
t_run slide --h1 "$D/huge.AT2" --mu 0.3; t_expect_rc motion-size 1
t_expect_err motion-size-msg "huge.AT2: file of 3221225472 bytes is larger than the 268435456 bytes"
rm -f "$D/huge.AT2" "$D/huge.ini"

# an interrupted run changes nothing and leaves nothing
cp -r "$D/res" "$D/res.before"
"$SEISLIDE_BIN" run floors -o "$D/res" --sets 7 -q --created 1700000000 >/dev/null 2>&1 &
pid=$!
sleep 1; kill -TERM $pid; wait $pid; rc=$?
[ "$rc" -ne 0 ] && t_pass || t_fail "interrupted run exit $rc"
# the floor-result cache (DIR/.seislide-cache, docs/plant.md) keeps the floors finished before
# the signal, so that a rerun resumes from them; the outputs themselves are untouched
diff -r -x .seislide-cache "$D/res.before" "$D/res" >/dev/null && t_pass || t_fail "SIGTERM changed the output folder"
ls -a "$D" | grep -q '\.tmp-' && t_fail "SIGTERM left a temporary: $(ls -a "$D" | tr '\n' ' ')" || t_pass

# --created 0 and SOURCE_DATE_EPOCH=0: identical workbooks a second apart
same_twice() { # NAME ARGS...: run twice into the same folder, compare
  name=$1; shift
  "$SEISLIDE_BIN" run "$D/fl/01-ground.ini" -o "$D/c" --sets 2 --mu 0.2,0.4 -q "$@" && cp "$D/c/seislide-clearance.xlsx" "$D/c.xlsx"
  sleep 1
  "$SEISLIDE_BIN" run "$D/fl/01-ground.ini" -o "$D/c" --sets 2 --mu 0.2,0.4 -q "$@" && \
    cmp -s "$D/c.xlsx" "$D/c/seislide-clearance.xlsx" && t_pass || t_fail "$name: workbooks differ"
}
same_twice created0 --created 0
SOURCE_DATE_EPOCH=0; export SOURCE_DATE_EPOCH
same_twice source-date-epoch0
unset SOURCE_DATE_EPOCH
# floor ids as written: Excel's forbidden characters and an apostrophe in a sheet name, a
# comma in a CSV column name (quoted), only the file names made safe
mkdir -p "$D/odd"
cp floors/01-ground.ini "$D/odd/O'Brien [1]: nord.ini"
cp floors/02-el12.ini "$D/odd/a, b.ini"
t_run run "$D/odd" -o "$D/odd_out" --sets 2 --mu 0.1,0.3 -q; t_expect_rc odd-ids 0
[ -s "$D/odd_out/floor_O_Brien__1___nord.csv" ] && [ -s "$D/odd_out/floor_a__b.csv" ] && t_pass || t_fail "safe file names: $(ls "$D/odd_out" | tr '\n' ' ')"
grep -v '^#' "$D/odd_out/summary.csv" | head -1 | grep -qF "mu,O'Brien [1]: nord_clearance_mm,\"a, b_clearance_mm\"" && t_pass || t_fail "summary.csv columns: $(grep -v '^#' "$D/odd_out/summary.csv" | head -1)"
unzip -p "$D/odd_out/seislide-clearance.xlsx" xl/workbook.xml 2>/dev/null | grep -q "<sheet name=\"O&apos;Brien _1__ nord\"\|<sheet name=\"O'Brien _1__ nord\"" && t_pass || t_fail "sheet name: $(unzip -p "$D/odd_out/seislide-clearance.xlsx" xl/workbook.xml | grep -o '<sheet name="[^"]*"' | tr '\n' ' ')"
t_end
