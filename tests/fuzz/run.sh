#!/bin/sh
# tests/fuzz/run.sh SECONDS JOBS NAME... - run each libFuzzer target of
# build-fuzz/bin for SECONDS on a scratch copy of its seed corpus, JOBS
# targets at a time; print per target: executions, coverage (cov/ft), new
# corpus size and findings; exit 1 when any target found a crash.
secs=$1 jobs=$2
shift 2
mkdir -p build-fuzz/corpus build-fuzz/findings build-fuzz/logs
one() {
  n=$1
  mkdir -p "build-fuzz/corpus/$n" "build-fuzz/findings/$n"
  cp -n tests/fuzz/corpus/"$n"/* "build-fuzz/corpus/$n/" 2>/dev/null
  cp -n tests/fuzz/regress/"$n"/* "build-fuzz/corpus/$n/" 2>/dev/null
  ASAN_OPTIONS=detect_leaks=1 "build-fuzz/bin/$n" -max_total_time="$secs" \
    -artifact_prefix="build-fuzz/findings/$n/" -max_len=65536 -timeout=20 -rss_limit_mb=4096 \
    -print_final_stats=1 "build-fuzz/corpus/$n" > "build-fuzz/logs/$n.log" 2>&1
  rc=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "build-fuzz/logs/$n.log")
  cov=$(grep -o 'cov: [0-9]* ft: [0-9]*' "build-fuzz/logs/$n.log" | tail -1)
  found=$(ls "build-fuzz/findings/$n" | wc -l)
  echo "$n: ${secs} s, $execs executions, $cov, corpus $(ls "build-fuzz/corpus/$n" | wc -l), findings $found (exit $rc)"
  [ "$rc" -eq 0 ] && [ "$found" -eq 0 ]
}
status=0
pids=""
for n in "$@"; do
  one "$n" &
  pids="$pids $!"
  if [ "$(echo $pids | wc -w)" -ge "$jobs" ]; then
    for p in $pids; do wait "$p" || status=1; done
    pids=""
  fi
done
for p in $pids; do wait "$p" || status=1; done
[ $status -eq 0 ] && echo "fuzz: no findings" || echo "fuzz: FINDINGS in build-fuzz/findings (turn each into tests/fuzz/regress/NAME/)"
exit $status
