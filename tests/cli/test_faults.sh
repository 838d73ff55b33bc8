#!/bin/sh
# Fault injection (docs/reliability.md): a plant run killed with SIGKILL at
# seeded random moments and at chosen system calls (strace), each followed by
# a rerun into the same folder; a file size limit; an unwritable cache; runs
# sharing one cache while one of them dies. (A flipped or truncated cache entry:
# tests/cli/test_plant.sh.)
# FAULTS_SEED=N changes the random kill points; FAULTS_KILLS=N their number.
. "$(dirname "$0")/lib.sh"
t_suite cli_faults
D=$T_TMP/w; mkdir "$D"
B="$SEISLIDE_BIN"
SEED=${FAULTS_SEED:-26}
KILLS=${FAULTS_KILLS:-22}
OMP_NUM_THREADS=1; export OMP_NUM_THREADS # one thread: the runs are short and many
mkdir -p "$D/plant/bldA" "$D/plant/bldB"
cp floors/01-ground.ini floors/02-el12.ini "$D/plant/bldA/"
cp floors/03-el24.ini floors/04-roof36.ini "$D/plant/bldB/"
OPTS="--sets 2 --mu 0.1,0.3 --created 1700000000"
OLD="--sets 2 --mu 0.1,0.3 --created 1600000000" # the same floors' keys, other outputs
now_ms() { date +%s%N | cut -c1-13; }
# every run into out/ has one command line (the workbooks record it), so no -q: stderr is sent away
run_plant() { "$B" run "$D/plant" -o "$D/out" $OPTS; }
# the files of an output folder but its cache, sorted
files_of() { (cd "$1" 2>/dev/null && find . -path ./.seislide-cache -prune -o -type f -print | sort); }
# same_as DIR REF: the same files, every one (CSV and workbook) byte for byte
same_as() {
  [ -n "$(files_of "$2")" ] && [ "$(files_of "$1")" = "$(files_of "$2")" ] || return 1
  for f in $(files_of "$2"); do cmp -s "$1/$f" "$2/$f" || return 1; done
}
# what an output folder holds: none (nothing but a cache), old, new or MIXED
state_of() {
  if [ -z "$(files_of "$1")" ]; then echo none
  elif same_as "$1" "$D/old"; then echo old
  elif same_as "$1" "$D/ref"; then echo new
  else echo MIXED; fi
}
# same_csv DIR REF: every CSV of REF in DIR with the same lines but the command line (it names DIR)
same_csv() {
  for f in $(cd "$2" && find . -name '*.csv'); do
    [ -f "$1/$f" ] && [ "$(grep -v '^# command:' "$1/$f")" = "$(grep -v '^# command:' "$2/$f")" ] || return 1
  done
}
n_entries() { ls "$1" 2>/dev/null | grep -c '\.slr$'; }
# temporaries anywhere: beside the output folder, in it, in its cache
leftovers() { (ls -a "$D"; ls -a "$D/out"; ls -a "$D/out/.seislide-cache") 2>/dev/null | grep -E '\.tmp-|\.lock|\.stale-' | tr '\n' ' '; }

# ---- the reference: an uninterrupted run, and an older one into the same folder
t0=$(now_ms)
run_plant 2>/dev/null; rc=$?
T=$(($(now_ms) - t0))
[ $rc -eq 0 ] && [ "$(n_entries "$D/out/.seislide-cache")" -eq 4 ] && t_pass || t_fail "reference run: exit $rc"
cp -r "$D/out" "$D/ref"
"$B" run "$D/plant" -o "$D/out" $OLD 2>/dev/null && cp -r "$D/out" "$D/old" && ! same_as "$D/old" "$D/ref" && t_pass || t_fail "older outputs"
# the workbooks too are reproducible: a rerun from the cache gives the same bytes
run_plant 2>/dev/null && same_as "$D/out" "$D/ref" && t_pass || t_fail "a rerun from the cache differs from the first run"
# every number written is finite
if grep -v '^#' "$D"/ref/*.csv "$D"/ref/*/*.csv | grep -Eiq '(^|[,:])[+-]?(nan|inf|infinity)(,|$)'; then
  t_fail "a CSV holds a non-finite number"
else t_pass; fi

# ---- SIGKILL, then the same command again
# setup K: 0 no output folder; 1 the older outputs, no cache; 2 the older
# outputs with 2 of the 4 floors in their cache
setup() {
  rm -rf "$D/out" "$D"/.out.tmp-*
  [ "$1" -eq 0 ] && return
  cp -r "$D/old" "$D/out"
  if [ "$1" -eq 1 ]; then rm -rf "$D/out/.seislide-cache"; return; fi
  for e in $(ls "$D/out/.seislide-cache" | awk -v t="$2" 'NR % 2 == t % 2'); do rm -f "$D/out/.seislide-cache/$e"; done
}
KILLED=""
# after_kill TRIAL SETUP WHAT: check the folder the kill left, rerun, check the rerun
after_kill() {
  trial=$1; k=$2; what=$3
  st=$(state_of "$D/out")
  case "$k$st" in 0none|0new|1old|1new|2old|2new) t_pass ;;
    *) t_fail "kill $trial ($what, setup $k): the output folder is $st (seed $SEED)" ;; esac
  # the entries the rerun must reuse: in the cache, or in a killed run's fresh folder
  ne=$( (ls "$D/out/.seislide-cache"; ls "$D"/.out.tmp-*/.seislide-cache) 2>/dev/null | grep '\.slr$' | sort -u | wc -l)
  fresh=$(ls -d "$D"/.out.tmp-* 2>/dev/null | head -1)
  if [ "$RC" -eq 0 ]; then where="finished first"
  elif [ "$st" = new ]; then where="after the swap"
  elif [ -n "$fresh" ] && [ -n "$(files_of "$fresh")" ]; then where="writing the outputs"
  elif [ "$ne" -eq 4 ]; then where="after the last floor"
  else where="computing floor $((ne + 1))"; fi
  KILLED="$KILLED$trial:$what:$where; "
  run_plant > "$D/rerun.err" 2>&1; rc=$?
  [ $rc -eq 0 ] && same_as "$D/out" "$D/ref" && t_pass || t_fail "kill $trial ($what, setup $k, $where): rerun exit $rc, outputs $(state_of "$D/out") (seed $SEED): $(grep -v "floor '" "$D/rerun.err" | head -c 400)"
  grep -q "reused $ne of 4 floors" "$D/rerun.err" && t_pass || t_fail "kill $trial ($what, $where): $ne finished floors, the rerun says: $(grep -E 'reused|failed' "$D/rerun.err" | head -c 300)"
  grep -q "failed its check" "$D/rerun.err" && t_fail "kill $trial ($what): a damaged entry: $(grep 'failed its check' "$D/rerun.err")" || t_pass
  left=$(leftovers)
  [ -z "$left" ] && t_pass || t_fail "kill $trial ($what, $where): left after the rerun: $left"
  # every entry reads back
  run_plant > "$D/again.err" 2>&1 && grep -q "reused 4 of 4 floors" "$D/again.err" && same_as "$D/out" "$D/ref" &&
    [ "$(n_entries "$D/out/.seislide-cache")" -eq 4 ] && t_pass || t_fail "kill $trial ($what): the cache after the rerun: $(grep -E 'reused|failed' "$D/again.err")"
}

# random moments over the measured duration of a run (awk's generator, seeded)
i=0
for d in $(awk -v s="$SEED" -v n="$KILLS" -v t="$T" 'BEGIN { srand(s); for (i = 0; i < n; i++) printf "%d ", rand() * t * 1.05 }'); do
  i=$((i + 1)); k=$((i % 3))
  [ $k -eq 2 ] && d=$((d / 2)) # half the floors to compute
  setup $k $i
  "$B" run "$D/plant" -o "$D/out" $OPTS 2> "$D/killed.err" & pid=$! # not a function: $! is seislide
  sleep "$(awk -v d="$d" 'BEGIN { printf "%.3f", d / 1000 }')"
  kill -9 $pid 2>/dev/null; { wait $pid; RC=$?; } 2>/dev/null
  after_kill "r$i" $k "after ${d} ms"
done
# chosen moments: SIGKILL on entering the Nth call of a system call (strace),
# so that a kill falls inside a cache write and inside the swap
if command -v strace >/dev/null 2>&1 && strace -qq -o /dev/null true 2>/dev/null; then
  # the renames of a run: 4 entries, the output files, the cache into the fresh folder, the
  # fresh folder's manifest
  setup 1 0
  strace -f -qq -o "$D/trace" -e trace=rename "$B" run "$D/plant" -o "$D/out" $OPTS 2>/dev/null
  R=$(grep -c 'rename(' "$D/trace")
  j=0
  # SYSCALL:N:SETUP; fsync 1: an entry written, not yet renamed; fsync 2: renamed, its lock
  # held; unlink 4: every entry in place, the last lock held (the rerun computes nothing)
  for p in fsync:1:0 rename:1:1 fsync:2:2 unlink:4:1 fsync:5:1 rename:3:0 \
           $(awk -v s="$SEED" -v r="$R" 'BEGIN { srand(s + 1); for (i = 0; i < 3; i++) printf "rename:%d:%d ", 5 + int(rand() * (r - 5)), i % 2 }') \
           rename:$((R - 1)):1 rename:$R:1 renameat2:1:2 unlinkat:1:1; do
    j=$((j + 1)); call=${p%%:*}; k=${p##*:}; n=${p#*:}; n=${n%:*}
    setup $k $j
    { strace -f -qq -o /dev/null -e trace="$call" -e inject="$call":signal=SIGKILL:when="$n" \
        "$B" run "$D/plant" -o "$D/out" $OPTS 2> "$D/killed.err"; RC=$?; } 2>/dev/null
    [ $RC -ne 0 ] && t_pass || t_fail "strace: no kill at $p (exit $RC)"
    after_kill "s$j" $k "at $call #$n"
  done
  echo "cli_faults: $R renames per run; kill points (seed $SEED, a run ${T} ms): $KILLED"
else
  t_skip "strace absent or not allowed to trace: no kills at chosen system calls"
  echo "cli_faults: kill points (seed $SEED, a run ${T} ms): $KILLED"
fi

# ---- a file size limit: a clear error naming the file, exit 1, outputs intact
# (ulimit -f counts 512-byte blocks in POSIX shells; measured, not assumed)
sh -c 'ulimit -f 4; head -c 8192 /dev/zero > "$1"; :' sh "$D/probe" 2>/dev/null
BLK=$(($(wc -c < "$D/probe") / 4))
limited() { # BYTES ARGS...: run seislide under a file size limit
  lim=$(($1 / BLK)); shift
  (ulimit -f $lim; exec "$B" "$@" > "$T_OUT" 2> "$T_ERR"); T_RC=$?
}
T_OUT=$D/lim.out; T_ERR=$D/lim.err
rm -rf "$D/lim"; cp -r "$D/ref" "$D/lim"; cp -r "$D/ref" "$D/lim.before"
# every floor from the cache; the building workbooks (29 KB) cannot be written
limited 16384 run "$D/plant" -o "$D/lim" $OPTS; t_expect_rc fsize-workbook 1
t_expect_err fsize-workbook-named "lim/bldA/seislide-clearance.xlsx: cannot write the workbook"
diff -r "$D/lim" "$D/lim.before" >/dev/null && t_pass || t_fail "file size limit: the outputs changed"
# a floor table (1.7 kB) cannot be written
limited 1024 run "$D/plant" -o "$D/lim" $OPTS -q; t_expect_rc fsize-csv 1
t_expect_err fsize-csv-named "lim/bldA/floor_01-ground.csv: cannot write: File too large"
diff -r "$D/lim" "$D/lim.before" >/dev/null && t_pass || t_fail "file size limit (CSV): the outputs changed"
# another seed: every floor computed; its cache entry (7 kB) cannot be written
limited 4096 run "$D/plant" -o "$D/lim" $OPTS --seed 2 -q; t_expect_rc fsize-entry 1
t_expect_err fsize-entry-named "lim/.seislide-cache/[0-9a-f]{16}\.slr: cannot write a cache entry: File too large"
diff -r "$D/lim" "$D/lim.before" >/dev/null && t_pass || t_fail "file size limit (cache): the outputs changed"
ls -a "$D" "$D/lim/.seislide-cache" | grep -Eq '\.tmp-|\.lock' && t_fail "file size limit: temporaries left: $(ls -a "$D" "$D/lim/.seislide-cache" | grep -E 'tmp|lock')" || t_pass

# ---- an unwritable cache: a clear error naming it, exit 1, outputs intact
T_OUT=$D/c.out; T_ERR=$D/c.err
echo "not a folder" > "$D/afile"
t_run run "$D/plant" -o "$D/lim" $OPTS --cache "$D/afile"; t_expect_rc cache-file 1
t_expect_err cache-file-named "afile: cannot read the cache folder: Not a directory"
grep -q "failed its check" "$T_ERR" && t_fail "cache is a file: taken for damaged entries" || t_pass
t_run run "$D/plant" -o "$D/lim" $OPTS --cache "$D/afile/sub" -q; t_expect_rc cache-under-file 1
t_expect_err cache-under-file-named "afile/sub: cannot create the cache folder: Not a directory"
diff -r "$D/lim" "$D/lim.before" >/dev/null && t_pass || t_fail "unwritable cache: the outputs changed"
# a read-only cache folder: root writes anyway, so the run is made by nobody
U=65534
if [ "$(id -u)" -ne 0 ]; then
  mkdir "$D/ro" && chmod 0555 "$D/ro"
  t_run run "$D/plant" -o "$D/lim" $OPTS --cache "$D/ro" -q; t_expect_rc cache-ro 1
  t_expect_err cache-ro-named "ro: the cache folder is not writable"
elif command -v setpriv >/dev/null 2>&1 && setpriv --reuid=$U --regid=$U --clear-groups true 2>/dev/null &&
     setpriv --reuid=$U --regid=$U --clear-groups test -x "$B" 2>/dev/null; then
  chmod 0711 "$T_TMP"; chmod 0755 "$D"
  mkdir -p "$D/nob/ro" && cp -r "$D/ref" "$D/nob/out" && chown -R $U:$U "$D/nob" && chmod 0555 "$D/nob/ro"
  cp -r "$D/nob/out" "$D/nob.before"
  setpriv --reuid=$U --regid=$U --clear-groups "$B" run "$D/plant" -o "$D/nob/out" $OPTS --seed 2 --cache "$D/nob/ro" -q > "$T_OUT" 2> "$T_ERR"; T_RC=$?
  t_expect_rc cache-ro 1
  t_expect_err cache-ro-named "nob/ro: the cache folder is not writable"
  diff -r "$D/nob/out" "$D/nob.before" >/dev/null && t_pass || t_fail "read-only cache: the outputs changed"
  chmod 0700 "$T_TMP"
else
  t_skip "running as root without setpriv to another user: a chmod 0555 cache is writable to root; not tested"
fi

# ---- runs sharing one cache (two at once, both right, each floor once: tests/cli/test_plant.sh);
# here: the cache reads back, and a run whose partner dies holding a lock finishes alone
mkdir "$D/sh"
"$B" run "$D/plant" -o "$D/sh1" $OPTS --cache "$D/sh" 2> "$D/sh1.err" & p1=$!
"$B" run "$D/plant" -o "$D/sh2" $OPTS --cache "$D/sh" 2> "$D/sh2.err" & p2=$!
"$B" run "$D/plant" -o "$D/sh3" $OPTS --cache "$D/sh" 2> "$D/sh3.err" & p3=$!
wait $p1; r1=$?; wait $p2; r2=$?; wait $p3; r3=$?
[ $r1$r2$r3 = 000 ] && t_pass || t_fail "three runs on one cache: exit $r1 $r2 $r3"
nc=$(cat "$D"/sh[123].err | grep -c 'computed;')
[ "$nc" -eq 4 ] && t_pass || t_fail "three runs on one cache: $nc floors computed, 4 expected"
for o in sh1 sh2 sh3; do same_csv "$D/$o" "$D/ref" && t_pass || t_fail "three runs on one cache: $o differs"; done
t_run run "$D/plant" -o "$D/sh4" $OPTS --cache "$D/sh"; t_expect_rc shared-readback 0
t_expect_err shared-readback-all "reused 4 of 4 floors"
grep -q "failed its check" "$T_ERR" && t_fail "shared cache: damaged entry" || t_pass
# the holder of a lock killed: the other run breaks the lock of the dead process
mkdir "$D/sk"
"$B" run "$D/plant" -o "$D/sk1" $OPTS --cache "$D/sk" -q 2>/dev/null & p1=$!
i=0
while [ $i -lt 300 ] && ! ls "$D/sk" 2>/dev/null | grep -q '\.lock$'; do sleep 0.02; i=$((i + 1)); done
"$B" run "$D/plant" -o "$D/sk2" $OPTS --cache "$D/sk" 2> "$D/sk2.err" & p2=$!
sleep 0.2; kill -9 $p1 2>/dev/null; { wait $p1; } 2>/dev/null
wait $p2; r2=$?
[ $r2 -eq 0 ] && same_csv "$D/sk2" "$D/ref" && t_pass || t_fail "partner killed: exit $r2, outputs differ: $(tail -c 300 "$D/sk2.err")"
[ "$(n_entries "$D/sk")" -eq 4 ] && [ -z "$(ls -a "$D/sk" | grep -E 'lock|tmp')" ] && t_pass || t_fail "partner killed: the cache holds $(ls -a "$D/sk" | tr '\n' ' ')"
t_end
