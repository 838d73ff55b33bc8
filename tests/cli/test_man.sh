#!/bin/sh
# The manual page covers every command and every option its --help lists, and
# states every default the same as --help does.
. "$(dirname "$0")/lib.sh"
t_suite cli_man
M="$T_TMP/man.txt"
sed 's/\\-/-/g; s/\\(+-/+-/g' docs/seislide.1 > "$M"

# "OPTION<TAB>VALUE" for every "default VALUE" an option's text states: from a
# --help (mode=help: "  --opt ARG  text" and indented continuation lines) or
# from the command's .SS section of the manual page (mode=man: ".B --opt ARG" or
# ".BI", then text up to the next request). VALUE stops at a blank, , ; ) or :.
defaults() {
  awk -v mode="$1" -v cmd="$2" '
    function flush(  s, t) {
      if (key != "") {
        s = text
        while (match(s, /default [^ ,;):]+/)) {
          t = substr(s, RSTART + 8, RLENGTH - 8); sub(/\.$/, "", t)
          print key "\t" t
          s = substr(s, RSTART + RLENGTH)
        }
      }
      key = ""; text = ""
    }
    mode == "help" && /^  -/ { flush(); match($0, /--[a-z0-9-]+/); key = substr($0, RSTART, RLENGTH); text = $0; next }
    mode == "help" && /^   / && key != "" { text = text " " $0; next }
    mode == "help" { flush(); next }
    /^\.SS / { flush(); sec = $2; next }
    sec == cmd && /^\.BI? / { flush(); if (match($0, /--[a-z0-9-]+/)) { key = substr($0, RSTART, RLENGTH); text = "" }; next }
    /^\./ { flush(); next }
    key != "" { text = text " " $0 }
    END { flush() }' "$3"
}

nd=0
for c in run merge slide rock synth spectrum rg160 asce bench study components lookup verify; do
  grep -q "^\.SS $c\$" "$M" && t_pass || t_fail "no section for '$c' in docs/seislide.1"
  t_run "$c" --help; t_expect_rc "$c --help" 0
  missing=""
  for o in $(grep -o -- '--[a-z][a-z0-9-]*' "$T_OUT" | sort -u); do
    [ "$o" = --help ] && continue
    grep -q -- "$o\b" "$M" || missing="$missing $o"
  done
  [ -z "$missing" ] && t_pass || t_fail "docs/seislide.1 lacks options of '$c':$missing"
  defaults help "$c" "$T_OUT" > "$T_TMP/help.def"
  defaults man "$c" "$M" > "$T_TMP/man.def"
  nd=$((nd + $(wc -l < "$T_TMP/help.def")))
  wrong=$(grep -vxF -f "$T_TMP/man.def" "$T_TMP/help.def" | tr '\t' ' ' | tr '\n' ';')
  [ -z "$wrong" ] && t_pass || t_fail "docs/seislide.1 states another default than '$c --help' for:$wrong"
done
# the comparison must see the defaults at all (--help of run, synth, ... state dozens)
[ "$nd" -ge 40 ] && t_pass || t_fail "only $nd defaults found in the --help texts"

# --help names a manual page the user can open from the source tree
"$SEISLIDE_BIN" --help > "$T_OUT" 2>&1
grep -q "man -l docs/seislide.1" "$T_OUT" && t_pass || t_fail "--help does not say 'man -l docs/seislide.1'"
t_end
