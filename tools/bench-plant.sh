#!/bin/bash
# bench-plant.sh - `make bench-plant` (docs/plant.md, "Speed: make bench-plant"):
# N floors of tools/benchplant.c's building model run as one plant at 1 and
# 2 OpenMP threads and as 2 shards of 1 thread each (GNU parallel) plus
# merge; prints a markdown table: wall time, CPU time, sets, CPU per set,
# sets per floor, speed-up and efficiency against 1 thread; then a run with
# a fresh cache and an unchanged rerun that reads every floor from it; then the
# time split of the 1-thread run (synthesis, of which the other dampings'
# checks, NLTHA, statistics, ASCE) with the extra synthesis attempts per set,
# the example facility (floors/) on 2 threads in the same run, the plant /
# facility wall-time ratio and the projection to 500 floors.
#   BENCH_PLANT_FLOORS=N (default 12), BENCH_PLANT_OPTS="run options"
#   (default: the program's defaults, converged sets), BENCH_PLANT_DIR (scratch folder),
#   BENCH_PLANT_RUNS=threads (only the 1- and 2-thread runs and the facility: the
#   split, the ratio and the projection, without the shards and the cache runs).
set -eu
BIN=${1:-./seislide}
GEN=${2:-build/tools/benchplant}
N=${BENCH_PLANT_FLOORS:-12}
OPTS=${BENCH_PLANT_OPTS:-}
RUNS=${BENCH_PLANT_RUNS:-all}
case "$RUNS" in all|threads) ;; *) echo "bench-plant: BENCH_PLANT_RUNS must be all or threads, not '$RUNS'" >&2; exit 2 ;; esac
W=${BENCH_PLANT_DIR:-$(mktemp -d)}
mkdir -p "$W"
rm -rf "$W/ground" "$W/plant" "$W/out1" "$W/out2" "$W/parts" "$W/merged" "$W/outc"
"$BIN" synth --rg160 1 --count 3 --seed 1 -o "$W/ground" -q >/dev/null
"$GEN" "$W/ground" "$N" "$W/plant" >/dev/null
TIMEFORMAT='%R %U %S'
run() { # label, then the command; prints "wall cpu"
  local t
  t=$( { time "$@" >/dev/null 2>&1; } 2>&1 | tail -1 )
  echo "$t" | awk '{ printf "%.2f %.2f\n", $1, $2 + $3 }'
}
# the sets column, counted from the end of the line (a floor's name may hold commas)
sets() { grep -v '^#' "$1/plant.csv" | awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "sets") k = NF - i; next }
                                              { s += $(NF - k) } END { print s }'; }
# (the 1-thread run without -q: its per-floor lines give the time split)
r1=$(OMP_NUM_THREADS=1 run sh -c '"$0" run "$1" -o "$2" --no-cache $3 2>"$4"' "$BIN" "$W/plant" "$W/out1" "$OPTS" "$W/out1.log")
r2=$(OMP_NUM_THREADS=2 run "$BIN" run "$W/plant" -o "$W/out2" --no-cache -q $OPTS)
if [ "$RUNS" = all ]; then
  mkdir -p "$W/parts"
  rs=$(OMP_NUM_THREADS=1 run parallel -j 2 "$BIN" run "$W/plant" --shard {}/2 -o "$W/parts/{}" --no-cache -q $OPTS ::: 1 2)
  rm_=$(run "$BIN" merge "$W"/parts/1 "$W"/parts/2 -o "$W/merged" -q)
  # each shard alone (CPU time: the balance, whatever the machine's load)
  c1=$(OMP_NUM_THREADS=1 run "$BIN" run "$W/plant" --shard 1/2 -o "$W/parts/1" --no-cache -q $OPTS)
  c2=$(OMP_NUM_THREADS=1 run "$BIN" run "$W/plant" --shard 2/2 -o "$W/parts/2" --no-cache -q $OPTS)
  # a run that fills a cache, then the unchanged rerun that reuses it
  k1=$(OMP_NUM_THREADS=1 run "$BIN" run "$W/plant" -o "$W/outc" -q $OPTS)
  k2=$(OMP_NUM_THREADS=1 run "$BIN" run "$W/plant" -o "$W/outc" -q $OPTS)
fi
# the example facility, 2 threads, in the same run (BENCH_PLANT_FACILITY: its folder)
FAC=${BENCH_PLANT_FACILITY:-floors}
rm -rf "$W/fac"
rf=$(OMP_NUM_THREADS=2 run "$BIN" run "$FAC" -o "$W/fac" --no-cache -q)
S=$(sets "$W/out1")
# the same CSV but for the lines that record the command and the time of the run
data() { grep -v -e '^# command: ' -e '^# created: ' "$1"; }
same=yes
for f in $(cd "$W/out1" && find . -name '*.csv'); do
  [ "$(data "$W/out1/$f")" = "$(data "$W/out2/$f")" ] &&
    { [ "$RUNS" = threads ] || [ "$(data "$W/out1/$f")" = "$(data "$W/merged/$f")" ]; } || same=no
done
w1=${r1% *}
echo "plant: $N floors ($(ls "$W/plant" | wc -l) building folders), $S motion sets, options '${OPTS:-defaults}'; nproc $(nproc)"
echo
echo "| run | wall, s | CPU, s | CPU per set, s | sets per floor | speed-up | efficiency |"
echo "|---|---|---|---|---|---|---|"
row() { echo "$2" | awk -v l="$1" -v s="$S" -v n="$N" -v w1="$w1" -v k="$3" '{
  printf "| %s | %.1f | %.1f | %.3f | %.1f | %.2f | %.0f %% |\n", l, $1, $2, $2 / s, s / n, w1 / $1, 100 * w1 / $1 / k }'; }
row "1 thread" "$r1" 1
row "2 threads (OMP_NUM_THREADS=2)" "$r2" 2
[ "$RUNS" = all ] && row "2 shards x 1 thread (GNU parallel)" "$rs" 2
echo
[ "$RUNS" = all ] && echo "$c1 $c2 ${r1#* }" | awk '{ m = $2 > $4 ? $2 : $4; printf "shards alone: CPU %.1f s and %.1f s (balance, largest / mean: %.3f); ideal 2-machine efficiency, CPU of 1 thread / (2 x largest shard CPU): %.0f %%\n", $2, $4, 2 * m / ($2 + $4), 100 * $5 / (2 * m) }'
echo "CPU of 2 threads / CPU of 1 thread: $(echo "${r2#* } ${r1#* }" | awk '{ printf "%.3f", $1 / $2 }') (threading overhead); load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
[ "$RUNS" = all ] && echo "merge of the 2 shards: $(echo "$rm_" | awk '{ printf "%.2f s wall", $1 }'); CSV outputs of all three runs identical (but for the command and time lines): $same"
[ "$RUNS" = threads ] && echo "CSV outputs of the 1- and 2-thread runs identical (but for the command and time lines): $same; shards and cache not run (BENCH_PLANT_RUNS=threads)"
[ "$RUNS" = all ] && echo "cache: the first run $(echo "$k1" | awk '{ printf "%.2f s wall", $1 }'), the unchanged rerun (every floor reused) $(echo "$k2 $k1" | awk '{ if ($1 >= 0.01) printf "%.2f s wall, %.0f x less", $1, $3 / $1; else printf "under 0.01 s wall" }')"
echo
# the split: the per-floor "thread time:" lines of the 1-thread run
split() { grep "thread time: synthesis" "$W/out1.log" | sed 's/.*synthesis \([0-9.]*\) s (of which the other dampings. checks \([0-9.]*\) s), NLTHA \([0-9.]*\) s, statistics \([0-9.]*\) s, ASCE and design \([0-9.]*\) s.*; \([0-9.]*\) extra synthesis attempts per set/\1 \2 \3 \4 \5 \6/'; }
nsets() { grep "motion sets" "$W/out1.log" | sed 's/.* \([0-9][0-9]*\) motion sets.*/\1/'; }
paste -d' ' <(split) <(nsets) | awk -v s="$S" -v c="${r1#* }" '
  { sy += $1; ck += $2; nl += $3; st += $4; as += $5; xa += $6 * $7; ns += $7 }
  END { t = sy + nl + st + as; if (t <= 0) t = 1
        printf "1 thread: CPU per set %.3f s; extra synthesis attempts per set %.2f; wall time split (summed over the floors): synthesis %.1f s (%.0f %%; of it the other dampings\047 checks %.1f s), NLTHA %.1f s (%.0f %%), statistics %.1f s (%.1f %%), ASCE and design %.1f s\n",
               c / s, ns ? xa / ns : 0, sy, 100 * sy / t, ck, nl, 100 * nl / t, st, 100 * st / t, as }'
w2=${r2% *}
wf=${rf% *}
echo "example facility ($FAC, 2 threads, the same run): $(echo "$rf" | awk '{ printf "%.2f s wall, %.1f s CPU", $1, $2 }'); plant / facility wall time (2 threads): $(echo "$w2 $wf" | awk '{ printf "%.1f", $1 / $2 }') (aim: at most 17, the facility under 10 s)"
echo "projection to 500 floors (2 threads, wall time x 500 / $N): $(echo "$w2 $N" | awk '{ printf "%.1f min", $1 * 500 / $2 / 60 }'); load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
