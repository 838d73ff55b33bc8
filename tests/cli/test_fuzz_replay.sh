#!/bin/sh
# The fuzz targets replayed over their seed corpus and every past finding
# (tests/fuzz/; docs/reliability.md): a reader that crashes, reads out of
# bounds (under `make asan`) or breaks its invariants on any of them fails.
. "$(dirname "$0")/lib.sh"
t_suite cli_fuzz_replay
bin=$(dirname "$SEISLIDE_TESTBIN")/fuzz-replay
n_targets=0
for t in "$bin"/fuzz_*; do
  [ -x "$t" ] || continue
  n=$(basename "$t")
  n_targets=$((n_targets + 1))
  if [ ! -d "tests/fuzz/corpus/$n" ]; then t_fail "$n: no seed corpus tests/fuzz/corpus/$n"; continue; fi
  if out=$("$t" "tests/fuzz/corpus/$n" "tests/fuzz/regress/$n" 2>&1); then
    t_pass
  else
    t_fail "$n on its corpus: $(echo "$out" | tail -3)"
  fi
done
if [ "$n_targets" -ge 2 ]; then t_pass; else t_fail "fuzz replay programs missing in $bin"; fi
t_end
