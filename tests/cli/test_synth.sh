#!/bin/sh
# End-to-end tests of `seislide synth`: help, usage errors, files and their
# headers, the report's columns and verdicts, reproducibility from the seed,
# read-back by other commands, failure reporting and exit codes.
. "$(dirname "$0")/lib.sh"
t_suite cli_synth
D=$T_TMP

# col FILE NAME: the column number of NAME in a CSV header
col() { head -1 "$1" | tr ',' '\n' | grep -nx "$2" | cut -d: -f1; }
# all_rows FILE NAME VALUE: every data row has VALUE in column NAME
all_rows() {
  c=$(col "$1" "$2"); [ -n "$c" ] || return 1
  awk -F, -v c="$c" -v v="$3" 'NR > 1 { n++; if ($c != v) bad++ } END { exit !(n > 0 && !bad) }' "$1"
}

# every row (of component $5 when given) has column $2 in [$3, $4]
col_in_range() {
  c=$(col "$1" "$2"); [ -n "$c" ] || return 1
  awk -F, -v c="$c" -v lo="$3" -v hi="$4" -v comp="${5:-}" \
    'NR > 1 && (comp == "" || $2 == comp) { n++; if (!($c + 0 >= lo && $c + 0 <= hi)) bad++ }
     END { exit !(n > 0 && !bad) }' "$1"
}

# ---- help and usage ---------------------------------------------------
t_run synth --help; t_expect_rc help 0; t_expect_out help-text "usage: seislide synth"
t_expect_out help-table "--max-corr X +largest \|correlation\| of two components \(default 0.16\)"
[ ! -s "$T_ERR" ] && t_pass || t_fail "--help wrote to stderr"
t_run --help; t_expect_out main-help-lists-synth "synth +spectrum-compatible"
t_run synth --rg160 0.3 --count 1 --seed 1 -o "$D/x" --bogus; t_expect_rc unknown 2; t_expect_err unknown-msg "unknown option '--bogus'"
t_run synth --count 1 --seed 1 -o "$D/x"; t_expect_rc no-target 2; t_expect_err no-target-msg "exactly one target"
t_run synth --rg160 0.3 --floor templates/floor.ini --count 1 --seed 1 -o "$D/x"; t_expect_rc two-targets 2
t_run synth --rg160 0.3 --count 1 --seed 1; t_expect_rc no-output 2; t_expect_err no-output-msg "-o DIR"
t_run synth --rg160 0.3 --seed 1 -o "$D/x"; t_expect_rc no-count 2; t_expect_err no-count-msg "--count"
t_run synth --rg160 0.3 --count 1 -o "$D/x"; t_expect_rc no-seed 2; t_expect_err no-seed-msg "--seed"
t_run synth --rg160 0.3 --count 0 --seed 1 -o "$D/x"; t_expect_rc count-0 2
t_run synth --rg160 -0.3 --count 1 --seed 1 -o "$D/x"; t_expect_rc negative-pga 2
t_run synth --rg160 0.3 --count 1 --seed x -o "$D/x"; t_expect_rc bad-seed 2
t_run synth --rg160 0.3 --count 1 --seed 1 --dt 0.02 -o "$D/x"; t_expect_rc dt-too-large 2; t_expect_err dt-msg "Nyquist"
t_run synth --rg160 0.3 --count 1 --seed 1 --max-corr 1.5 -o "$D/x"; t_expect_rc bad-limit 2; t_expect_err bad-limit-msg "--max-corr"
t_run synth --rg160 0.3 --count 1 --seed 1 --damping 0.3 -o "$D/x"; t_expect_rc rg-damping 2
t_run synth --rg160 0.3 --count 1 --seed 1 --format xls -o "$D/x"; t_expect_rc bad-format 2
t_run synth --rg160 0.3 --match a.AT2 --seed 1 -o "$D/x"; t_expect_rc match-and-seed 2
[ ! -e "$D/x" ] && t_pass || t_fail "output folder created on a usage error"

# ---- RG 1.60: files, headers, report ----------------------------------
OUT=$D/new/sub
t_run synth --rg160 0.3 --count 2 --seed 5 -o "$OUT"; t_expect_rc rg160 0
t_expect_err rg160-summary "6 motions, every check passed \(seed 5\)"
for k in 01 02; do for c in h1 h2 v; do
  [ -s "$OUT/set${k}_$c.AT2" ] && t_pass || t_fail "missing set${k}_$c.AT2"
done; done
sed -n 3p "$OUT/set01_h1.AT2" | grep -q "^ACCELERATION TIME SERIES IN UNITS OF G" && t_pass || t_fail "AT2 units line"
sed -n 4p "$OUT/set01_h1.AT2" | grep -q "^NPTS= 4001, DT= 0.005 SEC" && t_pass || t_fail "AT2 NPTS line: $(sed -n 4p "$OUT/set01_h1.AT2")"
sed -n 2p "$OUT/set01_v.AT2" | grep -q "RG 1.60 vertical.*seed 5" && t_pass || t_fail "AT2 title: $(sed -n 2p "$OUT/set01_v.AT2")"
R=$OUT/report.csv
head -1 "$R" | grep -q "^set,component,file,target,seed,attempt,iterations,damping,f_lo_hz,f_hi_hz,points,min_ratio," && t_pass || t_fail "report header: $(head -1 "$R")"
head -1 "$R" | grep -q ",ok_below,ok_above,ok_run,ok_d5_75,ok_duration,ok_end,ok_pga,ok_corr,ok_peaks,ok_psd,pass$" && t_pass || t_fail "report verdict columns"
[ "$(wc -l < "$R")" -eq 7 ] && t_pass || t_fail "report rows $(wc -l < "$R")"
all_rows "$R" pass 1 && t_pass || t_fail "not every motion passed"
all_rows "$R" seed 5 && t_pass || t_fail "seed not echoed"
all_rows "$R" points 271 && t_pass || t_fail "not 271 points checked"
# the PGA is not pinned: PGA/ZPA reported, within [0.75, 1.3]; few peaks near it
all_rows "$R" zpa_g 0.3 && t_pass || t_fail "ZPA not echoed"
col_in_range "$R" pga_zpa 0.75 1.3 && t_pass || t_fail "PGA/ZPA outside [0.75, 1.3]"
col_in_range "$R" peaks_above_0.9pga 1 5 && t_pass || t_fail "more than 5 peaks above 0.9 PGA"
c=$(col "$R" min_ratio); awk -F, -v c="$c" 'NR > 1 && !($c >= 0.9) { bad = 1 } END { exit bad }' "$R" && t_pass || t_fail "min ratio below 0.9"
c=$(col "$R" d5_75_s); awk -F, -v c="$c" 'NR > 1 && !($c >= 6) { bad = 1 } END { exit bad }' "$R" && t_pass || t_fail "D5-75 below 6 s"
ls -a "$OUT" | grep -q '\.tmp-' && t_fail "temporary file left behind" || t_pass

# the files are read back by the other commands (units from the header)
t_run spectrum "$OUT/set01_h1.AT2" --freq 50 --csv; t_expect_rc spectrum-reads 0
awk -F, 'NR == 2 { d = $2 - 0.3; if (d < 0) d = -d; exit !(d < 0.3 * 0.3) }' "$T_OUT" && t_pass || t_fail "PSA at 50 Hz far from the ZPA: $(cat "$T_OUT")"
t_run slide --h1 "$OUT/set01_h1.AT2" --h2 "$OUT/set01_h2.AT2" --v "$OUT/set01_v.AT2" --mu 0.2 --csv
t_expect_rc slide-reads 0

# ---- reproducible from the seed ----------------------------------------
t_run synth --rg160 0.3 --count 2 --seed 5 -q -o "$D/again"; t_expect_rc again 0
[ ! -s "$T_ERR" ] && t_pass || t_fail "-q still wrote: $(head -c 200 "$T_ERR")"
same=1; for f in set01_h1 set02_v; do cmp -s "$OUT/$f.AT2" "$D/again/$f.AT2" || same=0; done
[ $same -eq 1 ] && t_pass || t_fail "same seed, different files"
cmp -s "$R" "$D/again/report.csv" && t_pass || t_fail "same seed, different report"
OMP_NUM_THREADS=1 "$SEISLIDE_BIN" synth --rg160 0.3 --count 2 --seed 5 -q -o "$D/one" 2>/dev/null
cmp -s "$OUT/set02_h2.AT2" "$D/one/set02_h2.AT2" && t_pass || t_fail "one thread gives other bits"
t_run synth --rg160 0.3 --count 1 --seed 6 -q -o "$D/other"
cmp -s "$OUT/set01_h1.AT2" "$D/other/set01_h1.AT2" && t_fail "another seed, same motion" || t_pass

# ---- CSV motions; a floor ----------------------------------------------
t_run synth --floor templates/floor.ini --count 1 --seed 9 --format csv -q -o "$D/floor"; t_expect_rc floor 0
[ "$(head -1 "$D/floor/set01_h1.csv")" = "time_s,acc_g" ] && t_pass || t_fail "CSV header $(head -1 "$D/floor/set01_h1.csv")"
all_rows "$D/floor/report.csv" damping 0.05 && t_pass || t_fail "floor not matched at 5 %"
grep -q 'floor templates/floor.ini \[h2\]' "$D/floor/report.csv" && t_pass || t_fail "report target names the floor"
t_run spectrum "$D/floor/set01_v.csv" --freq 10 --csv; t_expect_rc csv-reads 0

# every other damping of a floor file (02-el12 gives 2, 5 and 10 %): matched
# at 5 %, the 2 % and 10 % tables checked on each motion's own spectra; the
# set-mean verdict on stderr
t_run synth --floor floors/02-el12.ini --count 2 --seed 3 -o "$D/el12"; t_expect_rc el12 0
t_expect_err el12-10pct "\[h1\] 10 % table against the motions' own 10 % spectra: set mean S/T"
all_rows "$D/el12/report.csv" other1_damping 0.02 && all_rows "$D/el12/report.csv" other2_damping 0.1 \
  && t_pass || t_fail "other dampings 0.02 and 0.1 not reported"
col_in_range "$D/el12/report.csv" other2_min_ratio 0.6 1.0 && col_in_range "$D/el12/report.csv" other2_max_ratio 1.0 1.5 \
  && t_pass || t_fail "10 % per-motion ratios implausible"
[ "$(col "$D/el12/report.csv" other2_ok_set_mean)" -gt "$(col "$D/el12/report.csv" pass)" ] && t_pass || t_fail "other-damping blocks not after pass"
awk -F, 'NR == 1 { n = NF } NF != n { bad++ } END { exit bad > 0 }' "$D/el12/report.csv" && t_pass || t_fail "rows of unequal width"
all_rows "$D/floor/report.csv" other1_damping 0.1 && [ -z "$(col "$D/floor/report.csv" other2_damping)" ] \
  && t_pass || t_fail "template floor: its 10 % table is the one other damping"

# a floor without the asked damping: error naming the file and section
t_run synth --floor tests/data/floors/good-small.ini --damping 0.07 --count 1 --seed 1 -o "$D/bad"
t_expect_rc floor-damping 1; t_expect_err floor-damping-msg "good-small.ini:[0-9]+: \[h1\] gives no spectrum at damping 0.07"

# ---- failures are reported, never passed --------------------------------
t_run synth --rg160 0.3 --count 1 --seed 1 --tol-below 0.001 --tol-above 0.001 --max-iter 1 --max-attempts 1 --aim 1 -o "$D/imp"
t_expect_rc impossible 1; t_expect_err impossible-msg "3 of 3 motions failed a check"
all_rows "$D/imp/report.csv" pass 0 && t_pass || t_fail "impossible limits passed"
all_rows "$D/imp/report.csv" lim_min_ratio 0.999 && t_pass || t_fail "limit not in the report"
# good-small's V (peak only 1.2 x ZPA): its spectrum is met only by a
# motion whose PGA is far below the claimed ZPA, and the report says so:
# below 1 - tol-below = 0.9, a disagreement larger than the spectral
# tolerance (measured 0.76 with seed 1, 0.45-0.69 with seeds 2-12)
t_run synth --floor tests/data/floors/good-small.ini --count 1 --seed 1 --dt 0.01 --max-attempts 2 -q -o "$D/small"
col_in_range "$D/small/report.csv" pga_zpa 0 0.9 v && t_pass || t_fail "implausible V: PGA/ZPA not reported low"

# an output folder that cannot be made
t_run synth --rg160 0.3 --count 1 --seed 1 -o /proc/seislide-no/x; t_expect_rc unwritable 1; t_expect_err unwritable-msg "cannot create"

# ---- a recorded motion ---------------------------------------------------
REC=$SEISLIDE_SHARED/records/RSN6_IMPVALL.I_I-ELC/RSN6_IMPVALL.I_I-ELC180.AT2
if [ -f "$REC" ]; then
  t_run synth --match "$REC" --rg160 0.4 -q -o "$D/match"; t_expect_rc match 0
  [ -s "$D/match/match_h1.AT2" ] && [ ! -e "$D/match/match_h2.AT2" ] && t_pass || t_fail "match files: $(ls "$D/match")"
  all_rows "$D/match/report.csv" pass 1 && t_pass || t_fail "matched record failed: $(cat "$D/match/report.csv")"
  all_rows "$D/match/report.csv" seed "" && t_pass || t_fail "records have no seed"
  sed -n 4p "$D/match/match_h1.AT2" | grep -q "DT= 0.01 SEC" && t_pass || t_fail "record step not kept"
  # El Centro (Peknold) at 0.02 s: resampled to 0.01 s
  PEK=$SEISLIDE_SHARED/records/ELCENTRO1940_NS_PEKNOLD/elCentro.AT2
  if [ -f "$PEK" ]; then
    t_run synth --match "$PEK" --rg160 0.4 -o "$D/pek"; t_expect_err resample-msg "resampled to dt 0.01 s"
    sed -n 4p "$D/pek/match_h1.AT2" | grep -q "DT= 0.01 SEC" && t_pass || t_fail "not resampled"
  else
    t_skip "$PEK not found: resampling not checked"
  fi
else
  t_skip "$REC not found (set SEISLIDE_SHARED): record matching not checked"
fi
t_run synth --match "$D/missing.AT2" --rg160 0.3 -o "$D/m2"; t_expect_rc match-missing 1; t_expect_err match-missing-msg "missing.AT2"

t_end
