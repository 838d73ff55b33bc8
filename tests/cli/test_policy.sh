#!/bin/sh
# End-to-end test of the clearance policy through the CSV files (docs/run.md,
# step 6: nltha = the NLTHA design value, asce = the ASCE design value,
# envelope = the larger of the two, the NLTHA one where ASCE is undefined).
# One floor (the roof: ASCE above NLTHA at mu 0.4-0.75, below elsewhere),
# 5 sets, 16 friction values, for each non-default policy: the clearance of
# summary.csv (shown to the digit of its standard error: within half a
# shown step, 0.5 mm) and of the floor's CSV (every digit: within 1e-4 mm)
# must equal what the policy prescribes from the floor CSV's
# nltha_design_mm and asce_design_mm; floors.csv names the policy. The check
# can fail: the rows where the two design values differ by more than 1 mm
# are counted and must be there (a summary that wrote the NLTHA design value
# for the envelope would differ by up to 116 mm).
. "$(dirname "$0")/lib.sh"
t_suite cli_policy
D=$T_TMP
for pol in envelope asce; do
  t_run run floors/04-roof36.ini -o "$D/$pol" --policy "$pol" --sets 5 --mu-range 0.05:0.8:0.05 \
    --created 0 -q
  t_expect_rc "run --policy $pol" 0
  F=$D/$pol/floor_04-roof36.csv; S=$D/$pol/summary.csv
  grep -v '^#' "$F" | head -1 | tr -d '\r' | grep -q '^mu,mu_g_over_zpa,nltha_mean_mm,nltha_sd_mm,nltha_design_mm,nltha_design_se_mm,nltha_design_lo90_mm,nltha_design_hi90_mm,asce_best_mm,asce_design_mm,cap_mm,clearance_mm,' \
    && t_pass || t_fail "$pol: floor CSV header: $(grep -v '^#' "$F" | head -1)"
  grep -v '^#' "$S" | head -1 | tr -d '\r' | grep -q '^mu,04-roof36_clearance_mm$' \
    && t_pass || t_fail "$pol: summary.csv header: $(grep -v '^#' "$S" | head -1)"
  grep -q ",$pol," "$D/$pol/floors.csv" && t_pass || t_fail "$pol: floors.csv does not name the policy"
  grep -v '^#' "$F" | tr -d '\r' | awk -F, 'NR > 1 { print $1, $5, $10, $12 }' >"$D/f.$pol"
  grep -v '^#' "$S" | tr -d '\r' | awk -F, 'NR > 1 { print $1, $2 }' >"$D/s.$pol"
  paste -d' ' "$D/f.$pol" "$D/s.$pol" | awk -v pol="$pol" '
    { mu = $1; dn = $2; da = $3; full = $4; mu2 = $5; shown = $6; n++
      if (pol == "asce") want = da
      else want = (da == "" || dn + 0 >= da + 0) ? dn : da
      if (da != "" && (dn - da > 1 || da - dn > 1)) differ++
      d1 = full - want; if (d1 < 0) d1 = -d1
      d2 = shown - want; if (d2 < 0) d2 = -d2
      if (mu != mu2 || want == "" || full == "" || shown == "" || d1 > 1e-4 || d2 > 0.5 + 1e-9) {
        bad++; msg = msg sprintf(" [mu %s: NLTHA %s ASCE %s, want %s, floor CSV %s, summary %s]",
                                 mu, dn, da, want, full, shown) } }
    END { if (n != 16 || differ < 3 || bad) { print n " rows, " differ " differ, " bad " wrong:" msg; exit 1 } }' \
    >"$D/bad.$pol" && t_pass || t_fail "--policy $pol: clearance: $(head -c 600 "$D/bad.$pol")"
done
t_end
