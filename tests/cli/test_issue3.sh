#!/bin/sh
# End-to-end tests of `seislide spectrum`, `seislide rg160` and
# `seislide asce` (issue 3): help, usage errors, column names, closed-form
# values, statuses, and messages naming file and line.
. "$(dirname "$0")/lib.sh"
t_suite cli_issue3
D=$T_TMP

# near(FILE, ROW, COL, EXPECTED, TOL): CSV field within an absolute tolerance
near() {
  awk -F, -v r="$2" -v c="$3" -v e="$4" -v t="$5" \
    'NR == r { d = $c - e; if (d < 0) d = -d; ok = (d <= t) } END { exit !ok }' "$1"
}

# ---- help and usage ---------------------------------------------------
for cmd in spectrum rg160 asce; do
  t_run $cmd --help; t_expect_rc "$cmd-help" 0; t_expect_out "$cmd-help-text" "usage: seislide $cmd"
  [ ! -s "$T_ERR" ] && t_pass || t_fail "$cmd --help wrote to stderr"
  t_run $cmd --bogus; t_expect_rc "$cmd-unknown" 2; t_expect_err "$cmd-unknown-msg" "unknown option '--bogus'"
done
t_run spectrum; t_expect_rc spectrum-no-file 2
# options and help come from one table per command (cli.h): -h is --help,
# a missing value is a usage error naming the option, every listed option
# is accepted, and the defaults shown are the code's
for cmd in spectrum rg160 asce study bench; do
  t_run $cmd -h; t_expect_rc "$cmd-h" 0; t_expect_out "$cmd-h-text" "usage: seislide $cmd"
done
t_run asce --rg160; t_expect_rc asce-missing-value 2; t_expect_err asce-missing-value-msg "option '--rg160' needs a value"
t_run asce --help
for o in rg160 floor h1 h2 units dt truncate mu mu-range fs pgd pgv csv; do
  grep -q -- "--$o\b" "$T_OUT" && t_pass || t_fail "asce --help does not list --$o"
done
t_expect_out asce-fs-default "--fs F +factor of safety on the best estimate \(default 2\)"
t_run asce --rg160 0.3 --mu 0.1 --fs 0; t_expect_rc asce-bad-fs 2; t_expect_err asce-bad-fs-msg "--fs '0' must be a number > 0"
t_run rg160 --help; t_expect_out rg160-grid-default "--fmin HZ, --fmax HZ +frequency range \(default 0.1 to 50 Hz\)"
t_run spectrum --help; t_expect_out spectrum-operand "^  FILE\.\.\. +motions: PEER"
t_run bench --repeat 0; t_expect_rc bench-bad-repeat 2; t_expect_err bench-bad-repeat-msg "--repeat '0' must be an integer >= 1"
t_run rg160 --damping 0.05; t_expect_rc rg160-no-pga 2; t_expect_err rg160-no-pga-msg "--pga"
t_run rg160 --pga 0.3 --damping 0.2; t_expect_rc rg160-bad-damping 2; t_expect_err rg160-bad-damping-msg "outside"
t_run rg160 --pga 0.3 --freq 1 --fmin 2; t_expect_rc rg160-freq-and-grid 2
t_run asce --mu 0.1; t_expect_rc asce-no-input 2; t_expect_err asce-no-input-msg "exactly one input"
t_run asce --rg160 0.3 --floor templates/floor.ini --mu 0.1; t_expect_rc asce-two-inputs 2
t_run asce --rg160 0.3; t_expect_rc asce-no-mu 2; t_expect_err asce-no-mu-msg "--mu"
t_run asce --rg160 0.3 --mu -0.1; t_expect_rc asce-negative-mu 2
t_run asce --rg160 0.3 --mu 0.1 --units g; t_expect_rc asce-units-without-motions 2
t_run asce --h1 x --mu 0.1; t_expect_rc asce-one-motion 2; t_expect_err asce-one-motion-msg "all three"

# ---- rg160: columns and the REFERENCE.md checkpoints ------------------
t_run rg160 --pga 0.3 --damping 0.10 --csv; t_expect_rc rg160-csv 0
[ "$(head -1 "$T_OUT")" = "f_hz,psa_g" ] && t_pass || t_fail "rg160 header '$(head -1 "$T_OUT")'"
[ "$(wc -l < "$T_OUT")" -eq 272 ] && t_pass || t_fail "rg160 rows $(wc -l < "$T_OUT")"
near "$T_OUT" 2 1 0.1 1e-12 && t_pass || t_fail "first frequency $(sed -n 2p "$T_OUT")"
near "$T_OUT" 272 2 0.3 1e-9 && t_pass || t_fail "ZPA at 50 Hz $(sed -n 272p "$T_OUT")"
t_run rg160 --pga 1 --damping 0.05,0.10 --freq 1,5,20 --csv; t_expect_rc rg160-checkpoints 0
[ "$(head -1 "$T_OUT")" = "f_hz,psa_g_z0.05,psa_g_z0.1" ] && t_pass || t_fail "two dampings header '$(head -1 "$T_OUT")'"
near "$T_OUT" 2 2 1.4739 5e-5 && near "$T_OUT" 3 2 2.8369 5e-5 && near "$T_OUT" 4 2 1.4474 5e-5 &&
  near "$T_OUT" 2 3 1.1305 5e-5 && near "$T_OUT" 3 3 2.0658 5e-5 && near "$T_OUT" 4 3 1.2807 5e-5 &&
  t_pass || t_fail "RG 1.60 checkpoints: $(cat "$T_OUT")"
t_run rg160 --pga 0.5 --vertical --freq 40; t_expect_rc rg160-table 0
t_expect_out rg160-table-header "f_hz +psa_g"; t_expect_out rg160-vertical "vertical"

# ---- spectrum: a step of 1 g, the first peak on a sample --------------
awk 'BEGIN { for (i = 0; i < 300; i++) print 1.0 }' > "$D/step.txt"
F=$(awk 'BEGIN { printf "%.17g", 2.5 / sqrt(1 - 0.05 * 0.05) }')
t_run spectrum "$D/step.txt" --units g --dt 0.01 --damping 0.05 --freq "$F" --csv; t_expect_rc spectrum-step 0
[ "$(head -1 "$T_OUT")" = "f_hz,psa_g" ] && t_pass || t_fail "spectrum header '$(head -1 "$T_OUT")'"
near "$T_OUT" 2 2 1.854468 1e-6 && t_pass || t_fail "step PSA $(sed -n 2p "$T_OUT")"
cp "$D/step.txt" "$D/other.txt"
t_run spectrum "$D/step.txt" "$D/other.txt" --units g --dt 0.01 --damping 0.05,0.10 --csv; t_expect_rc spectrum-two 0
[ "$(head -1 "$T_OUT")" = "f_hz,psa_g_z0.05_step.txt,psa_g_z0.1_step.txt,psa_g_z0.05_other.txt,psa_g_z0.1_other.txt" ] &&
  t_pass || t_fail "two files header '$(head -1 "$T_OUT")'"
[ "$(wc -l < "$T_OUT")" -eq 272 ] && t_pass || t_fail "default grid rows $(wc -l < "$T_OUT")"
t_run spectrum "$D/step.txt" --units g --dt 0.01 --all --freq 1,10 --csv; t_expect_rc spectrum-all 0
[ "$(head -1 "$T_OUT")" = "f_hz,psa_g,sd_m,sa_abs_g" ] && t_pass || t_fail "--all header '$(head -1 "$T_OUT")'"
t_run spectrum "$D/step.txt" --units g --dt 0.01 --freq 1; t_expect_rc spectrum-table 0
t_expect_out spectrum-table-header "f_hz +psa_g"
t_run spectrum "$D/step.txt" --dt 0.01; t_expect_rc spectrum-no-units 1; t_expect_err spectrum-no-units-msg "step.txt.*unit"
t_run spectrum "$D/missing.AT2"; t_expect_rc spectrum-missing 1; t_expect_err spectrum-missing-msg "^seislide: .*missing.AT2"
t_run spectrum "$D/step.txt" --units g --dt 0.01 --damping 1.0; t_expect_rc spectrum-damping-1 2

# ---- asce on RG 1.60 --------------------------------------------------
t_run asce --rg160 0.3 --mu 0.005,0.055,0.1,0.2,0.5 --csv; t_expect_rc asce-rg160 0
[ "$(head -1 "$T_OUT")" = "mu,mu_e,cs_g,fes_hz,delta_best_m,delta_design_m,status,cap_m,newmark_sym_m,newmark_asym_m" ] &&
  t_pass || t_fail "asce header '$(head -1 "$T_OUT")'"
awk -F, 'NR == 2 { exit !($7 == "below_fmin+capped") }' "$T_OUT" && t_pass || t_fail "mu 0.005: $(sed -n 2p "$T_OUT")"
awk -F, 'NR == 3 { exit !($7 == "capped") }' "$T_OUT" && t_pass || t_fail "mu 0.055: $(sed -n 3p "$T_OUT")"
awk -F, 'NR == 6 { exit !($7 == "no_sliding" && $5 == 0 && $6 == 0 && $4 == "nan") }' "$T_OUT" &&
  t_pass || t_fail "mu 0.5: $(sed -n 6p "$T_OUT")"
# mu 0.1 by hand: D-C power law of RG 1.60 (H, 10 %) at 0.3 g
awk -F, 'NR == 4 { pi = 3.14159265358979; g = 9.80665; a = 0.3; w = 2 * pi * 0.25;
  sad = w * w * 1.70 * 36 * 0.0254 * a / g; p = log(2.28 * a / sad) / log(10); k = sad / 0.25 ^ p;
  cs = 2 * 0.1 * (1 - 0.4 * a); f = (cs / (sqrt(1.16) * k)) ^ (1 / p); d = cs * g / (2 * pi * f) ^ 2;
  r = $5 / d - 1; if (r < 0) r = -r; q = $4 / f - 1; if (q < 0) q = -q;
  cap = 1.5 * 1.4 * 36 * 0.0254 * a;
  exit !(r < 1e-6 && q < 1e-6 && 2 * d > cap && $7 == "capped" && ($6 / cap - 1) ^ 2 < 1e-12) }' "$T_OUT" &&
  t_pass || t_fail "mu 0.1 by hand: $(sed -n 4p "$T_OUT")"
t_run asce --rg160 0.3 --mu-range 0.1:0.3:0.1; t_expect_rc asce-table 0
t_expect_out asce-table-units "best_mm"; t_expect_out asce-table-input "RG 1.60"
t_run asce --rg160 0.3 --mu 0.2 --fs 3 --csv; t_expect_rc asce-fs 0
awk -F, 'NR == 2 { exit !($7 == "ok" && ($6 / $5 - 3) ^ 2 < 1e-12) }' "$T_OUT" && t_pass || t_fail "--fs 3: $(sed -n 2p "$T_OUT")"

# ---- asce on floor files ----------------------------------------------
t_run asce --floor templates/floor.ini --mu 0.1,0.5 --csv; t_expect_rc asce-floor 0
awk -F, 'NR == 2 { exit !($7 == "ok" && $8 == "nan") } NR == 3 { exit !($7 == "no_sliding") }' "$T_OUT" &&
  t_pass || t_fail "floor: $(cat "$T_OUT")"
t_run asce --floor templates/floor.ini --mu 0.1 --pgd 0.1 --csv; t_expect_rc asce-floor-pgd 0
awk -F, 'NR == 2 { exit !($7 == "capped" && $8 == 0.15 && $6 == 0.15) }' "$T_OUT" && t_pass || t_fail "floor cap: $(sed -n 2p "$T_OUT")"
t_run asce --floor tests/data/floors/bad-units.ini --mu 0.1; t_expect_rc asce-bad-floor 1
t_expect_err asce-bad-floor-msg "^seislide: tests/data/floors/bad-units.ini:4: unknown units"
sed 's/^sa_0.10 = /sa_0.07 = /' templates/floor.ini > "$D/no10.ini"
t_run asce --floor "$D/no10.ini" --mu 0.1; t_expect_rc asce-floor-no-10 1
t_expect_err asce-floor-no-10-msg "no10.ini:[0-9]+: \[h1\] has no 10 %-damped spectrum"

# ---- asce on three motions --------------------------------------------
awk 'BEGIN { pi = 3.14159265358979; for (i = 0; i < 1000; i++) { t = i * 0.01;
  printf "%.6f\n", 0.3 * sin(2 * pi * 1.5 * t) * exp(-0.2 * t) } }' > "$D/h1.txt"
awk 'BEGIN { pi = 3.14159265358979; for (i = 0; i < 1000; i++) { t = i * 0.01;
  printf "%.6f\n", 0.2 * sin(2 * pi * 2.7 * t + 1) * exp(-0.2 * t) } }' > "$D/h2.txt"
awk 'BEGIN { pi = 3.14159265358979; for (i = 0; i < 1000; i++) { t = i * 0.01;
  printf "%.6f\n", 0.1 * sin(2 * pi * 6.1 * t) * exp(-0.3 * t) } }' > "$D/v.txt"
t_run asce --h1 "$D/h1.txt" --h2 "$D/h2.txt" --v "$D/v.txt" --units g --dt 0.01 --mu 0.05,0.1,0.4 --csv
t_expect_rc asce-motions 0
awk -F, 'NR == 2 { exit !($8 != "nan" && $9 != "nan" && $10 != "nan" && $7 ~ /^(ok|capped)$/) }' "$T_OUT" &&
  t_pass || t_fail "motions: $(sed -n 2p "$T_OUT")"
awk -F, 'NR == 4 { exit !($7 == "no_sliding") }' "$T_OUT" && t_pass || t_fail "motions mu 0.4: $(sed -n 4p "$T_OUT")"
AV=$(awk '{ x = $1 < 0 ? -$1 : $1; if (x > m) m = x } END { printf "%.9g", m }' "$D/v.txt")
awk -F, -v av="$AV" 'NR == 2 { mue = 0.05 * (1 - 0.4 * av); d = $2 - mue; if (d < 0) d = -d; exit !(d < 1e-6) }' "$T_OUT" &&
  t_pass || t_fail "motions A_v = peak |V| ($AV g): $(sed -n 2p "$T_OUT")"
t_run asce --h1 "$D/h1.txt" --h2 "$D/h2.txt" --v "$D/v.txt" --dt 0.01 --mu 0.1; t_expect_rc asce-motions-no-units 1

t_end
