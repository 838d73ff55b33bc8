#!/bin/sh
# End-to-end tests of `seislide slide`: options, output columns, exit codes,
# messages naming file, line and value, and no output file on failure.
. "$(dirname "$0")/lib.sh"
t_suite cli_slide
D=$T_TMP

# a small two-column record in g: a 0.5 g rectangular pulse of 0.5 s
awk 'BEGIN { for (i = 0; i <= 300; i++) { a = (i >= 1 && i <= 50) ? 0.5 : 0; printf "%.3f %g\n", i * 0.01, a } }' > "$D/pulse.txt"

t_run slide --help;                            t_expect_rc help 0; t_expect_out help-text "usage: seislide slide"
t_run;                                   t_expect_rc no-args 2
t_run slide --h1 "$D/pulse.txt" --units g;     t_expect_rc no-mu 2; t_expect_err no-mu-msg "--mu"
t_run slide --h1 "$D/pulse.txt" --units g --mu 0.1 --bogus; t_expect_rc unknown-option 2; t_expect_err unknown-msg "unknown option '--bogus'"
t_run slide --h1 "$D/pulse.txt" --units furlongs --mu 0.1; t_expect_rc bad-unit 2
t_run slide --h1 "$D/pulse.txt" --units g --mu 0.1,x;      t_expect_rc bad-mu 2
t_run slide --h1 "$D/pulse.txt" --units g --mu -0.1;       t_expect_rc negative-mu 2

# CSV: required columns, and the textbook pulse value within O(dt/t0)
t_run slide --h1 "$D/pulse.txt" --units g --mu 0.1,0.6 --csv; t_expect_rc csv 0
t_expect_out csv-header "^mu,peak_m,residual_m,"
# V = 0.5 g * 0.5 s; U = V^2/(2 mu g)(1 - mu/0.5) for mu = 0.1
awk -F, 'NR == 2 { g = 9.80665; V = 0.5 * g * 0.5; U = V * V / (2 * 0.1 * g) * (1 - 0.1 / 0.5);
                   r = $2 / U - 1; if (r < 0) r = -r; exit !(r < 0.04) }' "$T_OUT" && t_pass || t_fail "pulse peak $(sed -n 2p "$T_OUT")"
awk -F, 'NR == 3 { exit !($2 == 0 && $NF == "no_sliding") }' "$T_OUT" && t_pass || t_fail "mu 0.6 above 0.5 g: $(sed -n 3p "$T_OUT")"

# units are never guessed
t_run slide --h1 "$D/pulse.txt" --mu 0.1; t_expect_rc no-units 1; t_expect_err no-units-msg "pulse.txt.*unit"

# --scale-pga: scaling to 1.0 g doubles the pulse; with mu doubled u doubles
t_run slide --h1 "$D/pulse.txt" --units g --mu 0.1 --csv; p1=$(awk -F, 'NR == 2 { print $2 }' "$T_OUT")
t_run slide --h1 "$D/pulse.txt" --units g --mu 0.2 --csv --scale-pga 1.0; p2=$(awk -F, 'NR == 2 { print $2 }' "$T_OUT")
awk -v a="$p1" -v b="$p2" 'BEGIN { r = b / (2 * a) - 1; if (r < 0) r = -r; exit !(r < 1e-7) }' && t_pass || t_fail "scale-pga: $p1 vs $p2"

# model and solver names (sl_model_parse, sl_smooth_solver_parse): unknown ones are usage
# errors; the plastic reference model is not the exact engine (its elastic stage, U_y = 1e-4 m,
# changes the peak by a little but not by nothing)
t_run slide --h1 "$D/pulse.txt" --units g --mu 0.1 --model elastic; t_expect_rc model-unknown 2
t_run slide --h1 "$D/pulse.txt" --units g --mu 0.1 --model smooth --solver euler; t_expect_rc solver-unknown 2
t_run slide --h1 "$D/pulse.txt" --units g --mu 0.1 --model smooth --solver rkf45 --csv; t_expect_rc solver-rkf45 0
t_run slide --h1 "$D/pulse.txt" --units g --mu 0.1 --model plastic --csv; t_expect_rc plastic 0
pp=$(awk -F, 'NR == 2 { print $2 }' "$T_OUT")
awk -v a="$p1" -v b="$pp" 'BEGIN { r = b / a - 1; if (r < 0) r = -r; exit !(r > 1e-9 && r < 0.05) }' && t_pass || t_fail "plastic $pp vs exact $p1"
# the table's header names the model that computed it (not "1-D exact" for a reference model)
t_run slide --h1 "$D/pulse.txt" --units g --mu 0.1 --model smooth; t_expect_rc smooth-table 0
t_expect_out smooth-header "^# 1-D, smoothed hysteretic reference model"
t_run slide --h1 "$D/pulse.txt" --units g --mu 0.1 --model plastic; t_expect_out plastic-header "^# 1-D, elastic-plastic reference model"
t_run slide --h1 "$D/pulse.txt" --units g --mu 0.1; t_expect_out exact-header "^# 1-D exact,"

# history: one mu only; written atomically; header names units
t_run slide --h1 "$D/pulse.txt" --units g --mu 0.1,0.2 --history "$D/h.csv"; t_expect_rc history-two-mu 2
[ ! -e "$D/h.csv" ] && t_pass || t_fail "history file written on usage error"
t_run slide --h1 "$D/pulse.txt" --units g --mu 0.1 --history "$D/h.csv"; t_expect_rc history 0
head -1 "$D/h.csv" | grep -q "^t_s,ux_m,uy_m,vx_m_s,vy_m_s,fx_over_w,fy_over_w$" && t_pass || t_fail "history header: $(head -1 "$D/h.csv")"
ls -a "$D" | grep -q '\.tmp-' && t_fail "temporary file left behind" || t_pass

# bad inputs: file, line and value named; exit 1; no history file
printf '0.00 0.1\n0.01 0.2\n0.02 abc\n0.03 0.1\n' > "$D/badtok.txt"
t_run slide --h1 "$D/badtok.txt" --units g --mu 0.1 --history "$D/bad.csv"; t_expect_rc bad-token 1
t_expect_err bad-token-msg "badtok.txt:3:.*abc"
[ ! -e "$D/bad.csv" ] && t_pass || t_fail "history written despite bad input"
printf '0.00 0.1\n0.01 nan\n' > "$D/nan.txt"
t_run slide --h1 "$D/nan.txt" --units g --mu 0.1; t_expect_rc nan 1; t_expect_err nan-msg "nan.txt:2:"
t_run slide --h1 "$D/missing.AT2" --mu 0.1; t_expect_rc missing 1; t_expect_err missing-msg "missing.AT2"
printf 'TITLE\nEVENT\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS=    10, DT=   .0100 SEC\n .1 .2 .3 .4 .5\n' > "$D/trunc.AT2"
t_run slide --h1 "$D/trunc.AT2" --mu 0.1; t_expect_rc truncated-at2 1; t_expect_err truncated-msg "trunc.AT2:.*(NPTS|10)"
printf 'TITLE\nEVENT\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS=     3, DT=   .0000 SEC\n .1 .2 .3\n' > "$D/dt0.AT2"
t_run slide --h1 "$D/dt0.AT2" --mu 0.1; t_expect_rc dt-zero 1; t_expect_err dt-zero-msg "dt0.AT2:4:"
awk 'BEGIN { for (i = 0; i <= 300; i++) printf "%.3f %g\n", i * 0.02, 0 }' > "$D/dt02.txt"
t_run slide --h1 "$D/pulse.txt" --h2 "$D/dt02.txt" --units g --mu 0.1; t_expect_rc mixed-dt 1
t_expect_err mixed-dt-msg "pulse.txt.*0.01.*dt02.txt.*0.02"
# different lengths: padded with zeros by default (said on stderr with the
# numbers; a zero H2 padded with zeros is the 1-D answer), cut with --truncate
awk 'BEGIN { for (i = 0; i <= 200; i++) printf "%.3f %g\n", i * 0.01, 0 }' > "$D/short.txt"
t_run slide --h1 "$D/pulse.txt" --h2 "$D/short.txt" --units g --mu 0.1 --csv; t_expect_rc mixed-length 0
t_expect_err mixed-length-msg "H2 .*short.txt: 201 samples \\(to 2 s\\) padded with zeros to 301 \\(to 3 s\\)"
P2=$(sed -n 2p "$T_OUT" | cut -d, -f2)
t_run slide --h1 "$D/pulse.txt" --units g --mu 0.1 --csv
P1=$(sed -n 2p "$T_OUT" | cut -d, -f2)
awk -v a="$P1" -v b="$P2" 'BEGIN { r = b / a - 1; if (r < 0) r = -r; exit !(a > 1 && r < 1e-3) }' && t_pass || t_fail "padded 2-D $P2 vs 1-D $P1"
t_run slide --h1 "$D/pulse.txt" --h2 "$D/short.txt" --units g --mu 0.1 --truncate; t_expect_rc truncate 0
t_expect_err truncate-msg "H1 .*pulse.txt: 301 samples \\(to 3 s\\) cut to 201 \\(to 2 s\\)"

# 2-D and one-way: options that do not fit are usage errors
t_run slide --h1 "$D/pulse.txt" --h2 "$D/pulse.txt" --units g --mu 0.1 --one-way; t_expect_rc one-way-2d 2
t_run slide --h1 "$D/pulse.txt" --units g --mu 0.1 --one-way --csv; t_expect_rc one-way 0

# real record, 3 components, when ../shared is present
R="$SEISLIDE_SHARED/records/RSN1063_NORTHR_RRS"
if [ -f "$R/Rinaldi228.AT2" ]; then
  t_run slide --h1 "$R/Rinaldi228.AT2" --h2 "$R/Rinaldi318.AT2" --v "$R/RinaldiUP.AT2" --mu 0.3 --csv
  t_expect_rc rinaldi 0
  awk -F, 'NR == 2 { exit !($2 > 0.05 && $2 < 5) }' "$T_OUT" && t_pass || t_fail "Rinaldi peak implausible: $(sed -n 2p "$T_OUT")"
else
  t_skip "../shared/records absent: Rinaldi end-to-end run skipped"
fi
t_end
