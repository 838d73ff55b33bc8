#!/bin/sh
# The example floors: every file in floors/ loads, and the generator
# reproduces them exactly (docs/example-floors.md).
. "$(dirname "$0")/lib.sh"
t_suite cli_floors
for f in floors/*.ini; do
  t_run asce --floor "$f" --mu 0.1,0.3 --csv; t_expect_rc "load $f" 0
done
mkdir -p "$T_TMP/floors"
if sh floors/make-example-floors.sh "$SEISLIDE_BIN" "$T_TMP/floors" 2>"$T_TMP/gen.err"; then
  t_pass
  for f in floors/*.ini; do
    if cmp -s "$f" "$T_TMP/floors/$(basename "$f")"; then t_pass; else t_fail "$f differs from the generator's output"; fi
  done
else
  t_fail "generator failed: $(head -c 300 "$T_TMP/gen.err")"
fi
t_end
