#!/bin/sh
# Run every test layer and print one verdict: "N passed, N failed, N skipped".
#  - unit and numerical tests: every binary $SEISLIDE_TESTBIN/test_*
#  - end-to-end tests of the command line: every tests/cli/*.sh
# Each prints its own "SUITE: N passed, N failed, N skipped" line.
# Real records are read from $SEISLIDE_SHARED (default: ../shared).
ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT" || exit 2
: "${SEISLIDE_BIN:=$ROOT/seislide}"
: "${SEISLIDE_TESTBIN:=$ROOT/build/tests}"
: "${SEISLIDE_SHARED:=$ROOT/../shared}"
export SEISLIDE_BIN SEISLIDE_TESTBIN SEISLIDE_SHARED
if [ ! -d "$SEISLIDE_SHARED/records" ]; then
  echo "note: $SEISLIDE_SHARED/records not found: tests on real records will be skipped"
fi
log=$(mktemp) || exit 2
trap 'rm -f "$log"' EXIT
status=0
for t in "$SEISLIDE_TESTBIN"/test_*; do
  [ -x "$t" ] || continue
  "$t" | tee -a "$log" || status=1
done
for t in tests/cli/*.sh; do
  [ -f "$t" ] || continue
  sh "$t" | tee -a "$log" || status=1
done
awk '/: [0-9]+ passed, [0-9]+ failed/ { for (i = 1; i <= NF; i++) {
       if ($(i+1) ~ /^passed/) p += $i; if ($(i+1) ~ /^failed/) f += $i;
       if ($(i+1) ~ /^skipped/) s += $i } }
     END { printf "%d passed, %d failed, %d skipped\n", p, f, s; exit (f > 0) }' "$log" || status=1
exit $status
