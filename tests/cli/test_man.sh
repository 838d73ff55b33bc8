#!/bin/sh
# The manual page covers every command and every option its --help lists.
. "$(dirname "$0")/lib.sh"
t_suite cli_man
M="$T_TMP/man.txt"
sed 's/\\-/-/g' docs/seislide.1 > "$M"
for c in run merge slide synth spectrum rg160 asce bench study; do
  grep -q "^\.SS $c\$" "$M" && t_pass || t_fail "no section for '$c' in docs/seislide.1"
  t_run "$c" --help; t_expect_rc "$c --help" 0
  missing=""
  for o in $(grep -o -- '--[a-z][a-z0-9-]*' "$T_OUT" | sort -u); do
    [ "$o" = --help ] && continue
    grep -q -- "$o\b" "$M" || missing="$missing $o"
  done
  [ -z "$missing" ] && t_pass || t_fail "docs/seislide.1 lacks options of '$c':$missing"
done
t_end
