#!/bin/sh
# Reproducible across machines (docs/reliability.md, "Across machines"): glibc
# picks FMA or non-FMA libm routines by CPU, and the program picks the AVX2 or
# the baseline instance of its vector kernels. A small plant run with the
# x86-64-v3 (AVX2, FMA) routines turned off (GLIBC_TUNABLES), then also with
# the baseline kernels (SEISLIDE_KERNELS=baseline), writes every CSV byte for
# byte as the plain run, apart from the recorded command line (it names the
# output folder); shards computed under the two choices merge to the same data.
. "$(dirname "$0")/lib.sh"
t_suite cli_machines
D=$T_TMP
B="$SEISLIDE_BIN"
NOFMA="glibc.cpu.hwcaps=-AVX2,-FMA"
mkdir -p "$D/plant/bldA" "$D/plant/bldB" "$D/parts"
cp floors/01-ground.ini floors/04-roof36.ini "$D/plant/bldA/"
cp floors/03-el24.ini "$D/plant/bldB/"
OPTS="--sets 3 --mu 0.05,0.1,0.2,0.3,0.5 --created 0 -q"

# the tunable takes effect here: ld.so stops using the x86-64-v3 libraries
LDSO=/lib64/ld-linux-x86-64.so.2
if [ -x "$LDSO" ] && grep -qw fma /proc/cpuinfo 2>/dev/null; then
  a=$("$LDSO" --list-diagnostics 2>/dev/null | grep '^dl_hwcaps_subdirs_active=')
  b=$(GLIBC_TUNABLES=$NOFMA "$LDSO" --list-diagnostics 2>/dev/null | grep '^dl_hwcaps_subdirs_active=')
  [ -n "$a" ] && [ "$a" != "$b" ] && t_pass ||
    t_skip "GLIBC_TUNABLES=$NOFMA changes nothing here ($a, $b): both runs use one libm"
else
  t_skip "no x86-64 CPU with FMA: the libm choice is not exercised"
fi

# same_data NAME A B: the same CSV files in A and B, each byte for byte but for
# its '# command:' line
same_data() {
  la=$(cd "$2" && find . -name '*.csv' | sort); lb=$(cd "$3" && find . -name '*.csv' | sort)
  [ -n "$la" ] && [ "$la" = "$lb" ] || { t_fail "$1: other files: $la / $lb"; return; }
  bad=""
  for f in $la; do
    grep -v '^# command: ' "$2/$f" > "$D/ca"; grep -v '^# command: ' "$3/$f" > "$D/cb"
    cmp -s "$D/ca" "$D/cb" || bad="$bad $f ($(diff "$D/ca" "$D/cb" | sed -n 2p | cut -c1-120))"
  done
  [ -z "$bad" ] && t_pass || t_fail "$1: differs in$bad"
}

"$B" run "$D/plant" -o "$D/ref" $OPTS --no-cache 2> "$D/err"; r=$?
[ $r -eq 0 ] && t_pass || t_fail "plain run: exit $r: $(head -c 300 "$D/err")"
env GLIBC_TUNABLES=$NOFMA "$B" run "$D/plant" -o "$D/nofma" $OPTS --no-cache 2> "$D/err"; r=$?
[ $r -eq 0 ] && t_pass || t_fail "run without FMA libm: exit $r: $(head -c 300 "$D/err")"
same_data no-fma-libm "$D/ref" "$D/nofma"
env GLIBC_TUNABLES=$NOFMA SEISLIDE_KERNELS=baseline "$B" run "$D/plant" -o "$D/base" $OPTS \
  --no-cache 2> "$D/err"; r=$?
[ $r -eq 0 ] && t_pass || t_fail "run with the baseline kernels: exit $r: $(head -c 300 "$D/err")"
same_data baseline-kernels "$D/ref" "$D/base"

# the end residuals of the motions are round-off here: printed as 0, never as 1e-15
grep -v '^#' "$D/ref/bldA/motion_quality.csv" | awk -F, '
  NR == 1 { for (i = 1; i <= NF; i++) { if ($i == "v_end_m_s") v = i; if ($i == "d_end_m") d = i }; next }
  $v != "0" || $d != "0" { bad++ } END { exit !(v && d && NR > 1 && !bad) }' && t_pass ||
  t_fail "motion_quality.csv: end residuals not printed as 0: $(grep -v '^#' "$D/ref/bldA/motion_quality.csv" | sed -n 2p)"

# two shards on "two machines", merged: the plain run's data
env GLIBC_TUNABLES=$NOFMA SEISLIDE_KERNELS=baseline "$B" run "$D/plant" --shard 1/2 \
  -o "$D/parts/1" $OPTS 2> "$D/err"; r1=$?
"$B" run "$D/plant" --shard 2/2 -o "$D/parts/2" $OPTS 2>> "$D/err"; r2=$?
[ $r1 -eq 0 ] && [ $r2 -eq 0 ] && t_pass || t_fail "shards: exit $r1 $r2: $(head -c 300 "$D/err")"
t_run merge "$D/parts/1" "$D/parts/2" -o "$D/merged" --created 0; t_expect_rc merge 0
same_data merged-shards "$D/ref" "$D/merged"
t_end
