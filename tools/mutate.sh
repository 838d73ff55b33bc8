#!/bin/sh
# mutate.sh [LIST] - mutation testing (`make mutate`).
#
# LIST (default tests/mutations.txt) holds one mutation a line:
#   FILE<TAB>ORIGINAL<TAB>REPLACEMENT<TAB>WHAT
# ORIGINAL is a code snippet that must occur exactly once in FILE (a snippet,
# not a line number, so that edits elsewhere in the file do not move it).
# Each mutation is applied to a scratch copy of the tree, built there
# incrementally, and the suites that can see FILE are run, cheapest first,
# until one fails (killed) or all pass (SURVIVED). The tree itself is never
# modified. Ends with one line "N mutations, M survived, E no longer apply
# (T)"; exit 0 only when none survived and every entry applied.
#
# Which suites can see FILE (the map; printed with each result):
#  - FILE a library source src/**/*.c (not src/cli): the unit-test binaries
#    build/tests/test_* that link its object (a global symbol defined in
#    build/src/**/FILE.o is defined in the binary: the static link pulled
#    the object in), and every tests/cli suite when ./seislide links it
#    (the CLI suites run the program and `make install`);
#  - FILE under src/cli: every tests/cli suite (only the program has it);
#  - anything else (a header, which any object may include): every suite.
# The unmutated tree is built and its whole `make test` run first (the
# baseline: it must pass, and its per-suite times order the suites); a suite
# that runs more than 4 x its baseline time (at least 60 s) is stopped and
# counts as killing the mutation (a mutation that hangs is caught).
#
# Entries that no longer apply (FILE missing, or ORIGINAL not found exactly
# once) are printed and counted as errors. After code moves between files,
# `sh tools/mutate.sh --repoint [LIST]` rewrites the FILE column of every
# entry whose snippet is no longer in its FILE but occurs exactly once in
# exactly one other file under src/ (and prints what it changed); review
# the diff, then run `make mutate`.
#
# Parallel: $SEISLIDE_MUTATE_JOBS (default 2) workers, each in its own
# scratch copy. INT/TERM stop every worker and its descendants at once (by
# their ids), remove the scratch copies and exit 130. Records: $SEISLIDE_SHARED (default
# ../shared).
ROOT=$(cd "$(dirname "$0")/.." && pwd)
SELF=$ROOT/tools/mutate.sh
: "${SEISLIDE_SHARED:=$ROOT/../shared}"
: "${SEISLIDE_MUTATE_JOBS:=2}"
export SEISLIDE_SHARED
TAB=$(printf '\t')

# The entry checks (and --repoint) in one place: python3 is already needed.
check_entries() { # check_entries MODE LIST TREE OUT: MODE check|repoint
  python3 - "$@" <<'PY'
import os, sys
mode, lst, tree, out = sys.argv[1:5]
lines = open(lst).read().split('\n')
def where(snippet):
    hits = []
    for d, _, fs in os.walk(os.path.join(tree, 'src')):
        for f in fs:
            if f.endswith(('.c', '.h')):
                p = os.path.join(d, f)
                c = open(p, errors='replace').read().count(snippet)
                if c:
                    hits.append((os.path.relpath(p, tree), c))
    return hits
ok, bad, changed = [], 0, 0
for k, line in enumerate(lines):
    if not line.strip() or line.startswith('#'):
        continue
    f = line.split('\t')
    if len(f) != 4:
        print('NO LONGER APPLIES  %s:%d: not FILE<TAB>ORIGINAL<TAB>REPLACEMENT<TAB>WHAT' % (lst, k + 1))
        bad += 1
        continue
    path = os.path.join(tree, f[0])
    n = open(path, errors='replace').read().count(f[1]) if os.path.isfile(path) else -1
    if n == 1:
        ok.append(line)
        continue
    hits = where(f[1])
    once = [h for h, c in hits if c == 1]
    if mode == 'repoint' and len(hits) == 1 and len(once) == 1:
        print('re-pointed  line %d: %s -> %s  (%s)' % (k + 1, f[0], once[0], f[3]))
        f[0] = once[0]
        lines[k] = '\t'.join(f)
        changed += 1
        continue
    why = 'file missing' if n < 0 else 'ORIGINAL found %d times' % n
    hint = ''
    if hits:
        hint = '; found in ' + ', '.join('%s (%d x)' % h for h in hits)
        if len(hits) == 1 and len(once) == 1:
            hint += ': re-point with `sh tools/mutate.sh --repoint`'
    print('NO LONGER APPLIES  %s:%d: %s: %s (%s%s)\n    ORIGINAL: %s' % (lst, k + 1, f[0], f[3], why, hint, f[1]))
    bad += 1
if mode == 'repoint':
    if changed:
        open(lst, 'w').write('\n'.join(lines))
    print('%d entries re-pointed, %d still do not apply' % (changed, bad))
else:
    open(out, 'w').write(''.join(l + '\n' for l in ok))
sys.exit(0 if bad == 0 else 1)
PY
}

# mutate.sh --worker DIR PARENT: take entries from PARENT/queue until none is
# left; apply, build and run them in the scratch copy DIR.
if [ "$1" = "--worker" ]; then
  W=$2; P=$3
  cd "$W" || exit 2
  export SEISLIDE_BIN="$W/seislide" SEISLIDE_TESTBIN="$W/build/tests" \
    SEISLIDE_MAKEVARS="BUILD=build PROG=seislide" SEISLIDE_LDFLAGS=""
  N=$(wc -l <"$P/queue")
  while :; do
    until mkdir "$P/lock" 2>/dev/null; do sleep 0.05; done
    i=$(cat "$P/next"); echo $((i + 1)) >"$P/next"
    rmdir "$P/lock"
    [ "$i" -le "$N" ] || break
    line=$(sed -n "${i}p" "$P/queue")
    file=${line%%"$TAB"*}; what=${line##*"$TAB"}
    t0=$(date +%s)
    cp -p "$file" "$W/.orig" || exit 2
    python3 - "$P/queue" "$i" <<'PY' || { echo "mutate: entry $i no longer applies in the copy"; exit 2; }
import sys
f = open(sys.argv[1]).read().split('\n')[int(sys.argv[2]) - 1].split('\t')
s = open(f[0]).read()
if s.count(f[1]) != 1:
    sys.exit(1)
open(f[0], 'w').write(s.replace(f[1], f[2]))
PY
    suites=$(awk -F"$TAB" -v f="$file" '$1 == f { print $2 }' "$P/map")
    targets=
    for s in $suites; do
      case $s in tests/cli/*) targets="$targets seislide" ;; *) targets="$targets build/tests/$s" ;; esac
    done
    case $file in *.c) ;; *) targets=all ;; esac
    verdict=
    if ! make -s -j2 $(echo $targets | tr ' ' '\n' | sort -u) >"$W/.log" 2>&1; then
      verdict="killed (does not build)"
    else
      for s in $suites; do
        lim=$(awk -v s="$(basename "$s")" '$1 == s { t = $2 } END { t = 4 * (t ? t : 60); print int(t < 60 ? 60 : t) }' "$P/times")
        case $s in
          tests/cli/*) timeout --foreground -k 5 "$lim" sh "$s" >"$W/.log" 2>&1 ;;
          *) timeout --foreground -k 5 "$lim" "build/tests/$s" >"$W/.log" 2>&1 ;;
        esac
        rc=$?
        if [ $rc -eq 124 ] || [ $rc -eq 137 ]; then
          verdict="killed by $(basename "$s") (timed out after $lim s)"; break
        fi
        if [ $rc -ne 0 ] || ! grep -Eq '^[^ ]+: [0-9]+ passed, 0 failed, [0-9]+ skipped$' "$W/.log"; then
          why=$(grep -m1 -E 'FAIL' "$W/.log" | sed -E 's/^ *FAIL //' | cut -c1-100)
          [ -n "$why" ] || why="exit $rc, no failed check printed"
          verdict="killed by $(basename "$s"): $why"; break
        fi
      done
      [ -n "$verdict" ] || verdict="SURVIVED"
    fi
    cp -p "$W/.orig" "$file" && touch "$file"
    n_s=$(echo $suites | wc -w)
    echo "[$i/$N] $verdict  ($file: $what; $n_s suites can see it; $(($(date +%s) - t0)) s)"
    printf '%s\t%s\n' "$i" "$verdict" >>"$P/results"
  done
  exit 0
fi

if [ "$1" = "--repoint" ]; then
  LIST=${2:-$ROOT/tests/mutations.txt}
  check_entries repoint "$LIST" "$ROOT" /dev/null
  exit $?
fi

LIST=${1:-$ROOT/tests/mutations.txt}
case $LIST in /*) ;; *) LIST=$PWD/$LIST ;; esac
T0=$(date +%s)
P=$(mktemp -d) || exit 2
# killtree SIG PID: PID and every descendant (children first), by id.
killtree() {
  for c in $(ps -o pid= --ppid "$2" 2>/dev/null); do killtree "$1" "$c"; done
  kill "-$1" "$2" 2>/dev/null
}
stop() {
  for c in $(ps -o pid= --ppid $$); do killtree TERM "$c"; done
  sleep 1
  for c in $(ps -o pid= --ppid $$); do killtree KILL "$c"; done
  wait 2>/dev/null
  rm -rf "$P"
}
# in_bg CMD...: run CMD in the background and wait for it, so that a trapped
# INT/TERM interrupts the wait at once (a foreground command would finish
# first); returns its status.
in_bg() { "$@" & _p=$!; wait "$_p"; }
trap 'echo "mutate: interrupted"; stop; exit 130' INT TERM
trap 'rm -rf "$P"' EXIT

n_all=$(grep -cvE '^(#|[[:space:]]*$)' "$LIST")
check_entries check "$LIST" "$ROOT" "$P/queue"
N=$(wc -l <"$P/queue")
bad=$((n_all - N))

W1=$P/w1
mkdir "$W1" || exit 2
(cd "$ROOT" && tar --exclude=./build --exclude=./build-asan --exclude=./build-fuzz --exclude=./seislide --exclude=./.git \
  --exclude=./output -cf - .) | (cd "$W1" && tar -xf -) || exit 2
echo "mutate: building the scratch copy"
in_bg sh -c 'cd "$1" && exec make -s -j2 all' sh "$W1" >"$P/build.log" 2>&1 || {
  echo "mutate: the unmutated tree does not build:"; tail -20 "$P/build.log"; exit 2; }

# The map: FILE -> suites that can see it (rule in the header).
mkdir "$P/nm"
for b in "$W1"/build/tests/test_* "$W1/seislide"; do
  [ -x "$b" ] && nm --defined-only "$b" | awk '{ print $NF }' | sort -u >"$P/nm/$(basename "$b")"
done
if [ "${SEISLIDE_MUTATE_BASELINE:-1}" = 0 ]; then
  echo "mutate: no baseline (SEISLIDE_MUTATE_BASELINE=0): suites in name order, 240 s limit"
  : >"$P/times"
else
  echo "mutate: baseline: the whole make test on the unmutated copy"
  in_bg sh -c 'cd "$1" && SEISLIDE_BIN="$1/seislide" SEISLIDE_TESTBIN="$1/build/tests" \
    SEISLIDE_MAKEVARS="BUILD=build PROG=seislide" SEISLIDE_LDFLAGS="" \
    SEISLIDE_TEST_TIMES="$2/times" exec sh tests/run.sh' sh "$W1" "$P" >"$P/baseline.log" 2>&1 || {
    echo "mutate: the unmutated tree fails its tests:"
    grep -E 'FAIL|failed, [1-9]' "$P/baseline.log" | head -20; exit 2; }
  echo "mutate: baseline $(tail -1 "$P/baseline.log") ($(($(date +%s) - T0)) s since the start)"
fi
cli=$(cd "$W1" && ls tests/cli/test_*.sh)
units=$(cd "$W1/build/tests" && ls test_* 2>/dev/null)
: >"$P/map"
cut -f1 "$P/queue" | sort -u | while read -r f; do
  s=
  case $f in
    src/cli/*.c) s=$cli ;;
    src/*.c)
      o=$W1/build/${f%.c}.o
      nm -g --defined-only "$o" 2>/dev/null | awk '{ print $NF }' | sort -u >"$P/obj"
      for u in $units; do grep -qxFf "$P/obj" "$P/nm/$u" && s="$s $u"; done
      grep -qxFf "$P/obj" "$P/nm/seislide" && s="$s $cli" ;;
    *) s="$units $cli" ;;
  esac
  # cheapest first: units before CLI suites, each by its baseline time
  s=$(for x in $s; do
        b=$(basename "$x")
        t=$(awk -v b="$b" '$1 == b { print $2 }' "$P/times")
        case $x in tests/cli/*) k=1 ;; *) k=0 ;; esac
        echo "$k ${t:-999} $x"
      done | sort -k1,1n -k2,2g | awk '{ print $3 }' | tr '\n' ' ')
  printf '%s\t%s\n' "$f" "$s" >>"$P/map"
done

echo 1 >"$P/next"
: >"$P/results"
# every copy made before any worker builds in w1 (a copy taken while make
# writes there would miss the files it renames)
k=2
while [ $k -le "$SEISLIDE_MUTATE_JOBS" ]; do
  [ -d "$P/w$k" ] || cp -a "$W1" "$P/w$k" || exit 2
  k=$((k + 1))
done
k=1
while [ $k -le "$SEISLIDE_MUTATE_JOBS" ]; do
  sh "$SELF" --worker "$P/w$k" "$P" &
  k=$((k + 1))
done
wait
survived=$(grep -c "${TAB}SURVIVED" "$P/results")
done_n=$(wc -l <"$P/results")
if [ "$done_n" -ne "$N" ]; then
  echo "mutate: only $done_n of $N mutations ran (a worker failed)"; bad=$((bad + N - done_n))
fi
if [ "$survived" -gt 0 ]; then
  echo "survived:"
  grep "${TAB}SURVIVED" "$P/results" | cut -f1 | while read -r i; do sed -n "${i}p" "$P/queue"; done
fi
T=$(($(date +%s) - T0))
echo "$n_all mutations, $survived survived, $bad no longer apply ($((T / 60)) min $((T % 60)) s, $SEISLIDE_MUTATE_JOBS jobs)"
[ "$survived" -eq 0 ] && [ "$bad" -eq 0 ]
