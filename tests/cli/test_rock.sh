#!/bin/sh
# End-to-end tests of `seislide rock`: options, output columns, exit codes,
# messages naming file, line and value, no output file on failure; and the
# engine against an independent integrator (tests/rock_ref.py: scipy's
# solve_ivp with events, rtol 1e-10) on recorded motions from
# $SEISLIDE_SHARED/records (skipped with a message when they or scipy are
# absent).
. "$(dirname "$0")/lib.sh"
t_suite cli_rock
D=$T_TMP
ROOT=$(cd "$(dirname "$0")/../.." && pwd)

# a 0.5 s half-sine pulse of 0.3 g, then zeros (two-column file in g)
awk 'BEGIN { for (i = 0; i <= 400; i++) { t = i * 0.01; a = (t <= 0.5) ? -0.3 * sin(3.14159265358979 * t / 0.5) : 0;
             printf "%.3f %.9g\n", t, a } }' > "$D/pulse.txt"

t_run rock --help; t_expect_rc help 0; t_expect_out help-text "usage: seislide rock"
t_run rock --h1 "$D/pulse.txt" --units g --base-m 0.4; t_expect_rc no-height 2; t_expect_err no-height-msg "cg-height-m"
t_run rock --units g --base-m 0.4 --cg-height-m 1; t_expect_rc no-h1 2; t_expect_err no-h1-msg "--h1"
t_run rock --h1 "$D/pulse.txt" --units g --base-m -1 --cg-height-m 1; t_expect_rc bad-base 2
t_run rock --h1 "$D/pulse.txt" --units g --base-m 0.4 --cg-height-m 1 --restitution 1.2; t_expect_rc bad-r 2
t_expect_err bad-r-msg "restitution '1.2'"
t_run rock --h1 "$D/pulse.txt" --units g --base-m 0.4 --cg-height-m 1 --orientation x; t_expect_rc bad-orient 2
t_run rock --h1 "$D/pulse.txt" --units g --base-m 0.4 --cg-height-m 1 --rtol 1e-4 --substeps 4; t_expect_rc rtol-substeps 2
t_run rock --h1 "$D/pulse.txt" --units g --base-m 0.4 --cg-height-m 1 --rtol 0.5; t_expect_rc bad-rtol 2
t_run rock --h1 "$D/pulse.txt" --units g --base-m 0.4 --cg-height-m 1 --bogus; t_expect_rc unknown 2
t_run rock --h1 "$D/pulse.txt" --base-m 0.4 --cg-height-m 1; t_expect_rc no-units 1; t_expect_err no-units-msg "pulse.txt.*unit"

# CSV: the trace lines, the header, 12 orientations 0 ... 165
t_run rock --h1 "$D/pulse.txt" --units g --base-m 0.4 --cg-height-m 1 --csv; t_expect_rc csv 0
sed -n 1p "$T_OUT" | grep -q '^# program: seislide ' && t_pass || t_fail "csv: first line $(sed -n 1p "$T_OUT")"
grep -q '^# command: seislide rock ' "$T_OUT" && t_pass || t_fail "csv: no command line"
grep -v '^#' "$T_OUT" | sed -n 1p | grep -q '^orientation_deg,peak_theta_rad,peak_theta_over_alpha,tipped,overturned,impacts,' \
  && t_pass || t_fail "csv header: $(grep -v '^#' "$T_OUT" | sed -n 1p)"
[ "$(grep -v '^#' "$T_OUT" | tail -n +2 | cut -d, -f1 | paste -sd' ')" = "0 15 30 45 60 75 90 105 120 135 150 165" ] \
  && t_pass || t_fail "orientations: $(grep -v '^#' "$T_OUT" | cut -d, -f1 | paste -sd' ')"
# H1 alone: the demand along the weak axis at phi is cos(phi) H1, so the
# rotation falls with the angle and 90 degrees stands still
awk -F, '!/^#/ && NR > 1 && $1 != "orientation_deg" { p[$1] = $2; s[$1] = $NF }
         END { exit !(p[0] > p[45] && p[45] > p[75] && p[90] == 0 && s[90] == "stands") }' "$T_OUT" \
  && t_pass || t_fail "cos(phi) H1: $(grep -v '^#' "$T_OUT" | cut -d, -f1,2,15 | paste -sd' ')"
# every number finite
grep -v '^#' "$T_OUT" | grep -Eiq 'nan|inf' && t_fail "csv has nan/inf" || t_pass

# the table and the verdict; one orientation
t_run rock --h1 "$D/pulse.txt" --units g --base-m 0.4 --cg-height-m 1; t_expect_rc table 0
t_expect_out verdict "^verdict: (stands|tips|overturns); worst orientation 0 deg"
t_run rock --h1 "$D/pulse.txt" --units g --base-m 0.4 --cg-height-m 1 --orientation 30 --csv; t_expect_rc one 0
[ "$(grep -vc '^#' "$T_OUT")" = 2 ] && t_pass || t_fail "one orientation: $(cat "$T_OUT")"
# a wide block never uplifts (b/h 0.6 > 0.3 g): stands
t_run rock --h1 "$D/pulse.txt" --units g --base-m 1.2 --cg-height-m 1; t_expect_out wide "^verdict: stands; .*never uplifts"
# a slender one overturns under a bigger pulse
t_run rock --h1 "$D/pulse.txt" --units g --base-m 0.2 --cg-height-m 1 --scale-pga 1.0; t_expect_out slender "^verdict: overturns"

# --restitution 0 rests at the first impact: impacts 1 in a free-rocking pulse case
t_run rock --h1 "$D/pulse.txt" --units g --base-m 0.4 --cg-height-m 1 --restitution 0 --orientation 0 --csv
awk -F, '!/^#/ && $1 == "0" { exit !($6 >= 1) }' "$T_OUT" && t_pass || t_fail "r = 0: $(tail -1 "$T_OUT")"

# --history: atomic, header, the samples and the events in time order
t_run rock --h1 "$D/pulse.txt" --units g --base-m 0.4 --cg-height-m 1 --history "$D/h.csv"; t_expect_rc history 0
head -1 "$D/h.csv" | grep -q '^t_s,theta_rad,omega_rad_s,event,omega_before_rad_s$' && t_pass || t_fail "history header: $(head -1 "$D/h.csv")"
grep -q ',uplift,' "$D/h.csv" && grep -q ',impact,' "$D/h.csv" && t_pass || t_fail "history events"
awk -F, 'NR > 1 && $1 + 0 < last - 1e-9 { bad = 1 } NR > 1 { last = $1 + 0 } END { exit bad }' "$D/h.csv" \
  && t_pass || t_fail "history not in time order"
ls -a "$D" | grep -q '\.tmp-' && t_fail "temporary file left behind" || t_pass

# bad inputs: file, line and value named; exit 1; no history file
printf '0.00 0.1\n0.01 0.2\n0.02 abc\n0.03 0.1\n' > "$D/badtok.txt"
t_run rock --h1 "$D/badtok.txt" --units g --base-m 0.4 --cg-height-m 1 --history "$D/bad.csv"; t_expect_rc bad-token 1
t_expect_err bad-token-msg "badtok.txt:3:.*abc"
[ ! -e "$D/bad.csv" ] && t_pass || t_fail "history written despite bad input"
t_run rock --h1 "$D/missing.AT2" --base-m 0.4 --cg-height-m 1; t_expect_rc missing 1; t_expect_err missing-msg "missing.AT2"

# a vertical that takes the floor below -g: a warning, finite numbers
awk 'BEGIN { for (i = 0; i <= 400; i++) printf "%.3f %g\n", i * 0.01, (i >= 100 && i <= 120) ? -1.5 : 0 }' > "$D/v.txt"
t_run rock --h1 "$D/pulse.txt" --v "$D/v.txt" --units g --base-m 0.4 --cg-height-m 1 --csv; t_expect_rc liftoff 0
t_expect_err liftoff-msg "g \\+ a_v < 0 at [0-9]+ samples"

# ---- against the independent integrator on recorded motions ----------------
PY=/usr/bin/python3
REC=$SEISLIDE_SHARED/records
if [ ! -d "$REC" ]; then
  t_skip "independent integrator: $REC not found"
elif ! "$PY" -c 'import scipy.integrate' 2>/dev/null; then
  t_skip "independent integrator: $PY with scipy not found (apt-get install python3-scipy)"
else
  # case: H1 [V] base height pga [r]
  while read -r h1 v b hh g r; do
    [ -f "$REC/$h1" ] || { t_skip "record $h1 not found"; continue; }
    vopt=""; [ "$v" != "-" ] && vopt="--v $REC/$v"
    ropt=""; [ -n "$r" ] && ropt="--restitution $r"
    args="--h1 $REC/$h1 $vopt --base-m $b --cg-height-m $hh $ropt --orientation 0 --csv"
    "$SEISLIDE_BIN" rock $args --scale-pga "$g" --history "$D/rh.csv" > "$D/c0" 2>/dev/null || { t_fail "rock $h1"; continue; }
    for d in -1e-6 1e-6 -1e-5 1e-5; do
      "$SEISLIDE_BIN" rock $args --scale-pga "$(awk -v g="$g" -v d="$d" 'BEGIN { printf "%.15g", g * (1 + d) }')" \
        | tail -1 >> "$D/cp"
    done
    "$PY" "$ROOT/tests/rock_ref.py" --h1 "$REC/$h1" $vopt --base-m "$b" --cg-height-m "$hh" $ropt \
      --scale-pga "$g" > "$D/py" || { t_fail "rock_ref.py $h1"; continue; }
    fp=$(grep -m1 ',peak,' "$D/rh.csv" | cut -d, -f1,2)
    # non-chaotic: the 4 perturbed inputs keep the flags and move the peak by < 1e-4
    if awk -F, -v c="$(tail -1 "$D/c0")" 'BEGIN { split(c, z, ","); bad = 0 }
          { if ($4 != z[4] || $5 != z[5] || ($2 - z[2]) ^ 2 > (1e-4 * z[2]) ^ 2) bad = 1 }
          END { exit bad }' "$D/cp"; then kind=tight; else kind=robust; fi
    rm -f "$D/cp"
    if awk -F, -v kind="$kind" -v fp="$fp" -v name="$h1 $b $hh $g $r" '
        FNR == NR { split($0, kv, "="); py[kv[1]] = kv[2]; next }
        /^#/ || $1 == "orientation_deg" { next }
        { split(fp, f, ","); bad = ""
          d = ($9 - py["t_uplift_s"]); if (d < 0) d = -d; if (d > 1e-6) bad = bad " t_uplift " $9 " vs " py["t_uplift_s"]
          fpk = f[2] < 0 ? -f[2] : f[2]; d = fpk / py["first_peak_rad"] - 1; if (d < 0) d = -d
          if (d > 1e-4) bad = bad " first_peak " fpk " vs " py["first_peak_rad"]
          if (kind == "tight") {
            d = $2 / py["peak_theta_rad"] - 1; if (d < 0) d = -d
            if (d > 1e-3) bad = bad " peak " $2 " vs " py["peak_theta_rad"]
            if ($4 != py["tipped"] || $5 != py["overturned"]) bad = bad " flags " $4 $5 " vs " py["tipped"] py["overturned"]
            if ($6 != py["impacts"]) bad = bad " impacts " $6 " vs " py["impacts"]
            if ($8 != py["uplifts"]) bad = bad " uplifts " $8 " vs " py["uplifts"]
          }
          if (bad != "") { print name " (" kind "):" bad > "/dev/stderr"; exit 1 } }' "$D/py" "$D/c0"; then
      t_pass
    else
      t_fail "against rock_ref.py: $h1 $b $hh $g $r ($kind)"
    fi
    echo "$kind" >> "$D/kinds"
  done <<EOF
RSN1063_NORTHR_RRS/Rinaldi228.AT2 - 0.6 1.0 0.5
RSN1063_NORTHR_RRS/Rinaldi228.AT2 RSN1063_NORTHR_RRS/RinaldiUP.AT2 0.4 1.0 0.6
RSN6_IMPVALL.I_I-ELC/RSN6_IMPVALL.I_I-ELC180.AT2 - 0.6 1.0 0.5
RSN77_SFERN_PUL/RSN77_SFERN_PUL164.AT2 - 0.3 1.0 0.4
RSN77_SFERN_PUL/RSN77_SFERN_PUL164.AT2 - 0.5 2.0 0.3 0.9
RSN1111_KOBE_NIS/RSN1111_KOBE_NIS000.AT2 - 0.2 0.5 0.5
RSN1111_KOBE_NIS/RSN1111_KOBE_NIS000.AT2 RSN1111_KOBE_NIS/RSN1111_KOBE_NIS-UP.AT2 0.12 0.3 0.3 1.0
EOF
  # the list must hold tightly compared (non-chaotic) cases
  echo "cli_rock: against rock_ref.py: $(grep -c tight "$D/kinds") cases compared tightly (non-chaotic), $(grep -c robust "$D/kinds") in what is robust"
  [ -f "$D/kinds" ] && grep -q tight "$D/kinds" && t_pass || t_fail "no non-chaotic case compared tightly"
fi
t_end
