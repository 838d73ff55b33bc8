#!/bin/sh
# Floor spectra as CSV tables (docs/formats-floor.md): the same spectra as
# INI and as CSV give byte-identical results; a folder of .ini and .csv
# floors runs both; every malformed CSV exits 1 naming file:line(:column)
# and writes nothing; the binary, huge and ZPA-inconsistent cases too.
. "$(dirname "$0")/lib.sh"
t_suite cli_floor_csv
D=$T_TMP
FAST="--mu 0.2,0.4 -q --created 1700000000"

# INI -> CSV, the numbers copied as text (continuation lines joined)
ini2csv() {
  awk '
function trim(s) { sub(/^[ \t]+/, "", s); sub(/[ \t\r]+$/, "", s); return s }
/^[;#]/ { next }
/^\[/ { sec = substr($0, 2, index($0, "]") - 2); key = ""; next }
/^[ \t]/ && key != "" { val[sec, key] = val[sec, key] " " trim($0); next }
/=/ { i = index($0, "="); key = trim(substr($0, 1, i - 1)); v = substr($0, i + 1)
      sub(/[ \t];.*/, "", v); val[sec, key] = trim(v)
      if (!((sec, key) in seen)) { seen[sec, key] = 1; order[sec] = order[sec] " " key }; next }
END {
  print "# name: " val["floor", "name"]; print "# units: " val["floor", "units"]
  if (("floor", "elevation_m") in val) print "# elevation_m: " val["floor", "elevation_m"]
  if (("floor", "description") in val) print "# description: " val["floor", "description"]
  if (("floor", "h2") in val) print "# h2: " val["floor", "h2"]
  nc = split("h1 h2 v", comps, " ")
  for (c = 1; c <= nc; c++) if ((comps[c], "zpa") in val) print "# zpa_" comps[c] ": " val[comps[c], "zpa"]
  hdr = "f_hz"; ncol = 0
  for (c = 1; c <= nc; c++) { s = comps[c]; if (!((s, "f_hz") in val)) continue
    nf = split(val[s, "f_hz"], f, /[ ,]+/); nk = split(order[s], ks, " ")
    for (k = 1; k <= nk; k++) if (ks[k] ~ /^sa_/) {
      hdr = hdr "," s "_" sprintf("%g", substr(ks[k], 4) * 100); ncol++
      split(val[s, ks[k]], tmp, /[ ,]+/); for (j = 1; j <= nf; j++) cell[ncol, j] = tmp[j] } }
  print hdr
  for (j = 1; j <= nf; j++) { row = f[j]; for (k = 1; k <= ncol; k++) row = row "," cell[k, j]; print row } }' "$1"
}

# 1. the same spectra, two formats: byte-identical CSV data (comment lines
#    name the floor file and its CRC, so they differ; floors.csv names the
#    file in a column, which is set aside)
data() { grep -v '^#' "$1" | sed -e "s#$D/ini/04-roof36.ini#FLOOR#" -e "s#$D/csv/04-roof36.csv#FLOOR#"; }
mkdir -p "$D/ini" "$D/csv"
cp floors/04-roof36.ini "$D/ini/04-roof36.ini"
ini2csv floors/04-roof36.ini > "$D/csv/04-roof36.csv"
t_run run "$D/ini" -o "$D/out-ini" --sets 6 $FAST; t_expect_rc "run ini" 0
t_run run "$D/csv" -o "$D/out-csv" --sets 6 $FAST; t_expect_rc "run csv" 0
n=0
for f in "$D/out-ini"/*.csv; do
  g="$D/out-csv/$(basename "$f")"
  if [ -f "$g" ] && [ "$(data "$f")" = "$(data "$g")" ]; then n=$((n + 1)); else t_fail "$(basename "$f"): INI and CSV floors differ: $(diff "$f" "$g" 2>&1 | grep -v '^[<>] #' | head -5)"; fi
done
[ "$n" -ge 3 ] && t_pass || t_fail "only $n CSV outputs compared"
# the comparison can fail: one value changed gives other data
sed 's/^1,0.5754,/1,0.5755,/' "$D/csv/04-roof36.csv" > "$D/roof-changed.csv"
grep -q '^1,0.5755,' "$D/roof-changed.csv" && t_pass || t_fail "the changed value was not written"
t_run run "$D/roof-changed.csv" -o "$D/out-chg" --sets 6 $FAST; t_expect_rc "run changed" 0
if [ "$(grep -v '^#' "$D/out-ini/summary.csv")" != "$(grep -v '^#' "$D/out-chg/summary.csv" | sed 's/roof-changed/04-roof36/g')" ]; then t_pass; else t_fail "a changed spectrum gave the same summary"; fi

# 2. a folder with .ini and .csv floors (any case of the extension) runs both
mkdir -p "$D/mix"
cp floors/01-ground.ini "$D/mix/"; cp "$D/csv/04-roof36.csv" "$D/mix/04-roof36.CSV"
t_run run "$D/mix" -o "$D/out-mix" --sets 2 $FAST; t_expect_rc "run mix" 0
[ -s "$D/out-mix/floor_01-ground.csv" ] && [ -s "$D/out-mix/floor_04-roof36.csv" ] && t_pass || t_fail "mixed folder: $(ls "$D/out-mix")"
# the templates load, as do synth --floor and asce --floor with CSV
t_run asce --floor templates/floor.csv --mu 0.1,0.3 --csv; t_expect_rc "asce template.csv" 0
t_run synth --floor templates/floor.csv --count 1 --seed 3 -o "$D/syn" -q; t_expect_rc "synth --floor csv" 0

# 3. every malformed CSV: exit 1, file:line(:column): message, nothing written
for f in tests/data/floors/bad-csv-*.csv; do
  t_run run "$f" -o "$D/bad" --sets 2 $FAST; t_expect_rc "$f" 1
  t_expect_err "$f message" "^seislide: $f:[0-9]+(:[0-9]+)?: "
  if [ ! -e "$D/bad" ]; then t_pass; else t_fail "$f: output written"; rm -rf "$D/bad"; fi
done
# a file over SL_FLOOR_MAX_BYTES (16 MiB), refused before it is read
cp tests/data/floors/good-small.csv "$D/huge.csv"; truncate -s 17M "$D/huge.csv"
t_run run "$D/huge.csv" -o "$D/bad" $FAST --sets 2; t_expect_rc huge 1
t_expect_err huge-msg "huge.csv: file of 17825792 bytes is larger than the 16777216 bytes"
[ ! -e "$D/bad" ] && t_pass || t_fail "huge: output written"
# binary and ZPA-inconsistent INI files (issue 25)
t_run run tests/data/floors/bad-binary.ini -o "$D/bad" $FAST --sets 2; t_expect_rc binary 1
t_expect_err binary-msg "bad-binary.ini:4: not a text file: NUL byte at line 4"
t_run run tests/data/floors/bad-zpa-end.ini -o "$D/bad" $FAST --sets 2; t_expect_rc zpa-end 1
t_expect_err zpa-end-msg "bad-zpa-end.ini:15: zpa: 1e-300 m/s2 is"
t_run run tests/data/floors/implausible-gal.ini -o "$D/bad" $FAST --sets 2; t_expect_rc gal 1
t_expect_err gal-msg "implausible-gal.ini:4: units = gal gives"
[ ! -e "$D/bad" ] && t_pass || t_fail "bad INI: output written"
# implausible values and a table short of 33 Hz without zpa, as INI (the CSV ones in 3.)
for f in tests/data/floors/bad-spike.ini tests/data/floors/bad-utf16.ini tests/data/floors/bad-short.ini; do
  t_run run "$f" -o "$D/bad" --sets 2 $FAST; t_expect_rc "$f" 1
  t_expect_err "$f message" "^seislide: $f:[0-9]+: "
  [ ! -e "$D/bad" ] && t_pass || { t_fail "$f: output written"; rm -rf "$D/bad"; }
done
t_expect_err short-says-what-to-do "bad-short.ini:8: .*extend the table to 33 Hz or more, or give zpa"

# 4. tables as engineers save them: a European spreadsheet's (';', decimal commas) and a
#    table of periods (T_s) give the template's results
t_run run templates/floor.csv -o "$D/out-tpl" --sets 2 $FAST; t_expect_rc "run template" 0
t_run run tests/data/floors/good-semicolon.csv -o "$D/out-semi" --sets 2 $FAST; t_expect_rc "run ;" 0
t_run run tests/data/floors/good-periods.csv -o "$D/out-per" --sets 2 $FAST; t_expect_rc "run T_s" 0
dat() { grep -v '^#' "$1" | tail -n +2; } # the data rows (the header names the floor)
[ -s "$D/out-semi/summary.csv" ] && [ "$(dat "$D/out-tpl/summary.csv")" = "$(dat "$D/out-semi/summary.csv")" ] &&
  t_pass || t_fail "';' table: other results than the template: $(diff "$D/out-tpl/summary.csv" "$D/out-semi/summary.csv" | head -4)"
[ -s "$D/out-per/summary.csv" ] && t_pass || t_fail "T_s table: no summary"

# 5. an unusual ZPA (inside 0.01-5 g): runs, warns on stderr naming file:line and the unit as
#    written, and the workbook's Notes say it again; a usual one gives no warning
sed 's/^# units: g$/# units: m\/s2/' templates/floor.csv > "$D/g-as-ms2.csv"
awk -F, -v OFS=, '/^# zpa_h1:/ { print "# zpa_h1: " 0.36 * 9.80665; next }
  /^#/ || /^f_hz/ { print; next } { for (i = 2; i <= NF; i++) $i = $i * 9.80665; print }' \
  templates/floor.csv > "$D/ms2-as-g.csv"
L=$(grep -n '^# units' "$D/g-as-ms2.csv" | cut -d: -f1)
t_run run "$D/g-as-ms2.csv" -o "$D/out-low" --sets 2 $FAST; t_expect_rc "g labelled m/s2" 0
t_expect_err low-warning "run: warning: $D/g-as-ms2.csv:$L: # units: m/s2 gives a horizontal ZPA of 0.0367 g, unusual for a floor"
t_run run "$D/ms2-as-g.csv" -o "$D/out-high" --sets 2 $FAST; t_expect_rc "m/s2 labelled g" 0
t_expect_err high-warning "ms2-as-g.csv:$L: # units: g gives a horizontal ZPA of 3.53 g, unusual for a floor"
notes() { python3 -c 'import sys, zipfile; sys.stdout.write(zipfile.ZipFile(sys.argv[1]).read("xl/sharedStrings.xml").decode())' "$1/seislide-clearance.xlsx"; }
notes "$D/out-low" | grep -q "units: m/s2 gives a horizontal ZPA of 0.0367 g, unusual for a floor" &&
  t_pass || t_fail "the low-ZPA warning is not in the workbook's Notes"
notes "$D/out-high" | grep -q "units: g gives a horizontal ZPA of 3.53 g, unusual for a floor" &&
  t_pass || t_fail "the high-ZPA warning is not in the workbook's Notes"
grep -q "unusual for a floor" "$T_ERR" && t_pass || t_fail "no warning"
t_run run templates/floor.csv -o "$D/out-tpl2" --sets 2 $FAST; t_expect_rc "usual ZPA" 0
! grep -q "unusual" "$T_ERR" && t_pass || t_fail "a usual ZPA warned: $(cat "$T_ERR")"
notes "$D/out-tpl2" | grep -q "unusual for a floor" && t_fail "a usual ZPA noted in the workbook" || t_pass

# 6. no physical floor spectrum is refused by the plausibility or the ZPA rules (docs/formats-floor.md,
#    "Plausibility"): the bench plant's 100 floors, the example, template and sharp floors,
#    and, when the records are there, single-record and mean floors of 3 records
#    (tools/plausfloors.c: one row per family, its third column the floors refused)
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILDDIR=$(echo "$SEISLIDE_MAKEVARS" | tr ' ' '\n' | sed -n 's/^BUILD=//p'); BUILDDIR=${BUILDDIR:-build}
# shellcheck disable=SC2086
if make -s -C "$ROOT" $SEISLIDE_MAKEVARS LDFLAGS="$SEISLIDE_LDFLAGS" "$BUILDDIR/tools/benchplant" \
     "$BUILDDIR/tools/plausfloors" > "$D/pf.make" 2>&1; then
  "$SEISLIDE_BIN" synth --rg160 1 --count 3 --seed 1 -o "$D/pfground" -q > /dev/null 2>&1
  "$ROOT/$BUILDDIR/tools/benchplant" "$D/pfground" 100 "$D/pfplant" > /dev/null 2>&1 || t_fail "benchplant failed"
  REC=${SEISLIDE_SHARED:-../shared}/records
  if [ -d "$REC" ]; then RECS="-r $REC -n 3"; else RECS="-r $D/none"; t_skip "no records: single-record floors not tried"; fi
  # shellcheck disable=SC2086
  "$ROOT/$BUILDDIR/tools/plausfloors" $RECS "$D/pfplant" floors templates/floor.ini templates/floor.csv tests/data/floors/sharp-8.ini > "$D/pf.txt" 2>&1
  fam() { awk -F'|' -v c="$1" '$3 ~ /^ *[0-9]+ *$/ { s += $c; k++ } END { print (c ? s : k) + 0 }' "$D/pf.txt"; }
  # none refused, neither by the plausibility rules nor by any other (a given
  # ZPA against the table's end, SL_FLOOR_ZPA_END_MIN/_MAX)
  rows=$(fam 0); n=$(fam 3); refused=$(( $(fam 4) + $(fam 5) ))
  [ "$rows" -ge 4 ] && [ "$n" -ge 107 ] && [ "$refused" -eq 0 ] && t_pass ||
    t_fail "physical floors: $refused of $n refused ($rows families): $(grep -A1 '^| ' "$D/pf.txt" | grep 'first refused' | head -c 600)"
else
  t_fail "make plausfloors: $(head -c 400 "$D/pf.make")"
fi
t_end
