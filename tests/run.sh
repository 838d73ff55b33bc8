#!/bin/sh
# Run every test layer and print one verdict: "N passed, N failed, N skipped".
#  - unit and numerical tests: every binary $SEISLIDE_TESTBIN/test_*
#  - end-to-end tests of the command line: every tests/cli/test_*.sh
# Each suite prints its own "SUITE: N passed, N failed, N skipped" line.
# The suites run in parallel, $SEISLIDE_TEST_JOBS at a time (default 3: the
# suites are a mix of CPU and waiting on LibreOffice, files and processes);
# each suite's output (stdout and stderr) is collected and printed whole when
# it ends, with its wall time. A suite that exits non-zero without a failed
# check, or prints no verdict line (a crash, a signal, an exit before its
# end), counts as one failure. Exit status 0 only when nothing failed.
# SEISLIDE_TEST_TIMES=FILE also writes "SUITE SECONDS" lines to FILE.
# Real records are read from $SEISLIDE_SHARED (default: ../shared).
ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT" || exit 2
: "${SEISLIDE_BIN:=$ROOT/seislide}"
: "${SEISLIDE_TESTBIN:=$ROOT/build/tests}"
: "${SEISLIDE_SHARED:=$ROOT/../shared}"
: "${SEISLIDE_TEST_JOBS:=3}"
export SEISLIDE_BIN SEISLIDE_TESTBIN SEISLIDE_SHARED

# run.sh --one OUTDIR SUITE: run one suite (a test binary or a tests/cli
# script), keep its output in OUTDIR, print it whole under a lock.
if [ "$1" = "--one" ]; then
  out=$2; suite=$3; name=$(basename "$suite")
  t0=$(date +%s.%N)
  case $suite in
    *.sh) sh "$suite" >"$out/$name.log" 2>&1 ;;
    *) "$suite" >"$out/$name.log" 2>&1 ;;
  esac
  rc=$?
  t1=$(date +%s.%N)
  secs=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }')
  verdict=$(grep -E '^[^ ]+: [0-9]+ passed, [0-9]+ failed, [0-9]+ skipped$' "$out/$name.log" | tail -1)
  if [ -z "$verdict" ]; then
    echo "$name: 0 passed, 1 failed, 0 skipped (exit $rc, no verdict line: crashed or stopped early)" \
      >>"$out/$name.log"
  elif [ $rc -ne 0 ] && echo "$verdict" | grep -q ' 0 failed'; then
    echo "$name: 0 passed, 1 failed, 0 skipped (exit $rc after '$verdict')" >>"$out/$name.log"
  fi
  echo "$name $secs" >"$out/$name.time"
  until mkdir "$out/.lock" 2>/dev/null; do sleep 0.1; done
  cat "$out/$name.log"
  echo "  ($name: $secs s)"
  rmdir "$out/.lock"
  exit 0
fi

if [ ! -d "$SEISLIDE_SHARED/records" ]; then
  echo "note: $SEISLIDE_SHARED/records not found: tests on real records will be skipped"
fi
out=$(mktemp -d) || exit 2
trap 'rm -rf "$out"' EXIT
trap 'exit 130' INT TERM
# Longest first (measured; a suite not named here runs after them), so that
# the last suite to start is a short one.
slow="tests/cli/test_faults.sh tests/cli/test_floor_csv.sh tests/cli/test_converge.sh
  tests/cli/test_outputs.sh tests/cli/test_outdirs.sh $SEISLIDE_TESTBIN/test_analysis tests/cli/test_plant.sh
  tests/cli/test_components.sh $SEISLIDE_TESTBIN/test_physical_floors tests/cli/test_workbook.sh
  tests/cli/test_run_errors.sh tests/cli/test_run.sh $SEISLIDE_TESTBIN/test_synth
  tests/cli/test_deliver.sh $SEISLIDE_TESTBIN/test_lookup tests/cli/test_synth.sh
  tests/cli/test_rock.sh"
{
  for t in $slow; do [ -e "$t" ] && echo "$t"; done
  for t in "$SEISLIDE_TESTBIN"/test_* tests/cli/test_*.sh; do
    [ -f "$t" ] || continue
    case $t in *.sh) ;; *) [ -x "$t" ] || continue ;; esac
    case " $(echo $slow) " in *" $t "*) continue ;; esac
    echo "$t"
  done
} >"$out/.suites"
t0=$(date +%s)
xargs -P "$SEISLIDE_TEST_JOBS" -I{} sh "$ROOT/tests/run.sh" --one "$out" {} <"$out/.suites"
t1=$(date +%s)
[ -n "$SEISLIDE_TEST_TIMES" ] && cat "$out"/*.time >"$SEISLIDE_TEST_TIMES"
echo "  ($(wc -l <"$out/.suites") suites, $SEISLIDE_TEST_JOBS at a time: $((t1 - t0)) s)"
cat "$out"/*.log | awk '/^[^ ]+: [0-9]+ passed, [0-9]+ failed, [0-9]+ skipped/ {
       p += $2; f += $4; s += $6 }
     END { printf "%d passed, %d failed, %d skipped\n", p, f, s; exit (f > 0) }'
