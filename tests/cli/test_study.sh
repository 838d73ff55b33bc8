#!/bin/sh
# End-to-end tests of `seislide study`: help, usage errors, a missing records
# folder (exit 1, nothing written), and a real run of the parts that take
# seconds: the report's sections, its data files, and agreement between the
# report's numbers and `seislide slide` on the same record.
. "$(dirname "$0")/lib.sh"
t_suite cli_study
D=$T_TMP

t_run study --help; t_expect_rc help 0; t_expect_out help-text "usage: seislide study"
t_run --help; t_expect_out main-help-lists-study "study +reproduce the source study"
t_run study --parts 6; t_expect_rc bad-part 2; t_expect_err bad-part-msg "--parts '6'"
t_run study --parts x,1; t_expect_rc bad-part-list 2
t_run study --bogus; t_expect_rc unknown 2; t_expect_err unknown-msg "unknown option '--bogus'"
t_run study extra; t_expect_rc extra-arg 2
t_run study --records "$D/none" -o "$D/out0" -q; t_expect_rc no-records 1
t_expect_err no-records-msg "$D/none: the records folder is missing"
[ ! -e "$D/out0/validation.md" ] && t_pass || t_fail "validation.md written without records"

if [ ! -d "$SEISLIDE_SHARED/records" ]; then
  t_skip "$SEISLIDE_SHARED/records not found (set SEISLIDE_SHARED): study run not checked"
  t_end; exit $?
fi
R=$SEISLIDE_SHARED/records
t_run study --records "$R" -o "$D/res" --parts 1,2 --no-plots -q; t_expect_rc run 0
V=$D/res/validation.md
grep -q "^## 1. Model validation" "$V" && t_pass || t_fail "section 1 missing"
grep -q "^## 2. El Centro" "$V" && t_pass || t_fail "section 2 missing"
grep -q "^## 3" "$V" && t_fail "section 3 written although not asked for" || t_pass
grep -q "^## 5. The study's quantitative claims" "$V" && t_pass || t_fail "claims table missing"
for f in p1_1d_engine p1_2d_smooth p2_xyz; do
  [ -s "$D/res/validation/$f.tsv" ] && t_pass || t_fail "$f.tsv missing"
done
[ -s "$D/res/validation/fig1_rinaldi_228.gp" ] && t_pass || t_fail "gnuplot script missing"
ls "$D/res/validation/"*.svg >/dev/null 2>&1 && t_fail "figures drawn with --no-plots" || t_pass
# The engine row of Rinaldi 228 + 318 equals `seislide slide` on the record
# (mm, 2 decimals in the report).
rep=$(awk -F'|' '$2 ~ /228 \+ 318/ && $3 ~ /engine/ { gsub(/ /, "", $4); print $4 }' "$V")
t_run slide --h1 "$R/RSN1063_NORTHR_RRS/Rinaldi228.AT2" --h2 "$R/RSN1063_NORTHR_RRS/Rinaldi318.AT2" --mu 0.3 --csv
cli=$(awk -F, 'NR == 2 { printf "%.2f", $2 * 1e3 }' "$T_OUT")
[ -n "$rep" ] && [ "$rep" = "$cli" ] && t_pass || t_fail "report $rep mm, slide $cli mm"
# The data file's peak equals the table's peak (the file is the history).
peak=$(awk '!/^#/ { v = $2 < 0 ? -$2 : $2; if (v > m) m = v } END { printf "%.2f", m * 1e3 }' \
  "$D/res/validation/p1_1d_engine.tsv")
rep1=$(awk -F'|' '$2 ~ /^ 228 $/ && $3 ~ /engine/ { gsub(/ /, "", $4); print $4 }' "$V")
[ "$peak" = "$rep1" ] && t_pass || t_fail "history peak $peak mm, report $rep1 mm"
# Sections 7 and 8 carry make rockfloors' and make tailfloors' tables as written,
# each in its own section, or say how to make them.
grep -q "^## 7. Rocking against physical floor motions" "$V" && t_pass || t_fail "section 7 missing"
grep -q "^## 8. The intensity tail near the sliding threshold" "$V" && t_pass ||
  t_fail "section 8 missing"
for t in rockfloors tailfloors; do
  grep -q "is not in this output folder: .make $t. makes it" "$V" && t_pass ||
    t_fail "without $t's tables validation.md does not say how to make them"
done
printf '| building | rows |\n|---|---|\n| rock-%s | 1 |\n' "$$" >"$D/res/validation/rocking_floors.md"
printf '| building | ratio |\n|---|---|\n| tail-%s | 1 |\n' "$$" >"$D/res/validation/tail_floors.md"
t_run study --records "$R" -o "$D/res" --parts 1 --no-plots -q; t_expect_rc rerun 0
sed -n '/^## 7/,/^## 8/p' "$V" | grep -qx "| rock-$$ | 1 |" && t_pass ||
  t_fail "section 7 does not carry validation/rocking_floors.md"
sed -n '/^## 8/,$p' "$V" | grep -qx "| tail-$$ | 1 |" && t_pass ||
  t_fail "section 8 does not carry validation/tail_floors.md"
grep -q "is not in this output folder" "$V" && t_fail "validation.md says carried tables are missing" || t_pass
t_end
