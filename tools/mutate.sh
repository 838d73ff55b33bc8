#!/bin/sh
# mutate.sh [LIST] - mutation testing: apply each single-line mutation of
# LIST (default tests/mutations.txt; lines FILE<TAB>ORIGINAL<TAB>REPLACEMENT<TAB>WHAT,
# ORIGINAL occurring exactly once in FILE) to a scratch copy of the tree,
# one at a time, build and run `make test` there, and report whether the
# tests killed it. Ends with one line "N mutations, M survived"; exit 0 when
# none survived. Takes minutes (one `make test` per mutation); the tree
# itself is never modified. The unit-test binaries run first and stop at the
# first failure; a mutation they all miss runs the whole `make test`. Records: $SEISLIDE_SHARED (default ../shared).
ROOT=$(cd "$(dirname "$0")/.." && pwd)
LIST=${1:-$ROOT/tests/mutations.txt}
case $LIST in /*) ;; *) LIST=$PWD/$LIST ;; esac
: "${SEISLIDE_SHARED:=$ROOT/../shared}"
export SEISLIDE_SHARED
W=$(mktemp -d) || exit 2
trap 'rm -rf "$W"' EXIT INT TERM
(cd "$ROOT" && tar --exclude=./build --exclude=./build-asan --exclude=./seislide --exclude=./.git \
  --exclude=./output -cf - .) | (cd "$W" && tar -xf -) || exit 2
cd "$W" || exit 2
make -s -j2 all >/dev/null 2>&1 || { echo "mutate: the unmutated tree does not build"; exit 2; }
n=0; survived=0; bad=0
TAB=$(printf '\t')
while IFS="$TAB" read -r file orig repl what; do
  case $file in ''|'#'*) continue ;; esac
  n=$((n + 1))
  cp "$file" "$W/.orig" 2>/dev/null || { echo "MISSING  $file: $what"; bad=$((bad + 1)); continue; }
  if ! python3 - "$file" "$orig" "$repl" <<'PY'
import sys
path, orig, repl = sys.argv[1:4]
s = open(path).read()
if s.count(orig) != 1:
    sys.exit(1)
open(path, "w").write(s.replace(orig, repl))
PY
  then
    echo "NOTFOUND $file: $what (the line changed: update tests/mutations.txt)"
    bad=$((bad + 1)); continue
  fi
  # the unit tests first, stopping at the first failure (most mutations
  # die there in seconds); only a mutation they all miss runs the whole
  # `make test` (the same verdict: every layer)
  verdict=
  if ! make -s -j2 all >"$W/.log" 2>&1; then
    verdict="killed (does not build)"
  else
    for t in build/tests/test_*; do
      if ! "$t" >"$W/.log" 2>&1; then
        verdict="killed by $(grep -m1 -E 'FAIL' "$W/.log" | sed -E 's/^ *FAIL //' | cut -c1-90)"
        break
      fi
    done
  fi
  if [ -z "$verdict" ]; then
    if make -s test >"$W/.log" 2>&1; then
      verdict="SURVIVED"; survived=$((survived + 1))
    else
      verdict="killed by $(grep -m1 -E 'FAIL' "$W/.log" | sed -E 's/^ *FAIL //' | cut -c1-90)"
    fi
  fi
  echo "$verdict  $file: $what"
  cp "$W/.orig" "$file"
  touch "$file"
done < "$LIST"
[ $bad -gt 0 ] && echo "mutate: $bad mutation(s) could not be applied"
echo "$n mutations, $survived survived"
[ $survived -eq 0 ] && [ $bad -eq 0 ]
