#!/bin/sh
# Outputs seislide owns (docs/reliability.md, docs/run.md): an output
# folder equal to, inside or holding any input is refused before any work
# (exit 2) and nothing anywhere changes; a non-empty folder seislide did not
# make is refused (exit 1) naming a file in it; a rerun into a folder
# seislide wrote keeps every file its manifest does not name (the same file:
# a hard link) and drops the outputs it no longer writes; missing parents are
# made; two runs on one folder: the second refuses naming the first; the GNU
# parallel and Slurm lines of docs/plant.md run as written.
. "$(dirname "$0")/lib.sh"
t_suite cli_outputs
D=$T_TMP/w; mkdir "$D"
ROOT=$(pwd)
B=$(cd "$(dirname "$SEISLIDE_BIN")" && pwd)/$(basename "$SEISLIDE_BIN")
OMP_NUM_THREADS=1; export OMP_NUM_THREADS
FAST="--sets 2 --mu 0.1,0.3 --created 1700000000 -q"
mkdir -p "$D/plant/bldA" "$D/plant/bldB" "$D/rec"
cp floors/01-ground.ini "$D/plant/bldA/"
cp floors/03-el24.ini "$D/plant/bldB/"
cp tests/data/motion/cms2.AT2 "$D/rec/"
ln -s plant "$D/link"
ln -s rec/cms2.AT2 "$D/m.AT2"
mkdir "$D/fl2" && ln -s ../plant/bldA/01-ground.ini "$D/fl2/g.ini"

# every path of a tree with its type, mode and link target, and every file's bytes
fp() { (cd "$1" && find . -printf '%p %y %m %l\n' | LC_ALL=C sort && find . -type f -print0 | LC_ALL=C sort -z | xargs -0 -r sha256sum); }
# t_run_in DIR ARGS: t_run from folder DIR
t_run_in() { d=$1; shift; T_OUT=$T_TMP/out; T_ERR=$T_TMP/err; (cd "$d" && "$B" "$@") >"$T_OUT" 2>"$T_ERR"; T_RC=$?; }
# refuse NAME ARGS: run from $WHERE (default $D): exit 2 naming the input, nothing under $D changed
refuse() {
  name=$1; shift; before=$(fp "$D")
  t_run_in "${WHERE:-$D}" "$@"; t_expect_rc "$name" 2
  t_expect_err "$name-msg" "(is|is inside|holds) the input '.*': give an output apart from every input"
  [ "$(fp "$D")" = "$before" ] && t_pass || t_fail "$name: the folder $D changed"
}
# same_csv DIR REF: every CSV of REF in DIR, the same lines but the command line
same_csv() {
  [ -n "$(cd "$2" && find . -name '*.csv')" ] || return 1
  for f in $(cd "$2" && find . -name '*.csv'); do
    [ -f "$1/$f" ] && [ "$(grep -v '^# command:' "$1/$f")" = "$(grep -v '^# command:' "$2/$f")" ] || return 1
  done
}

# ---- -o equal to, inside or holding an input: exit 2, nothing changed --------
refuse equal run plant -o plant $FAST
refuse equal-abs run "$D/plant/" -o "$D/plant/" $FAST
refuse inside run plant -o plant/bldA $FAST
refuse inside-new run plant -o plant/bldA/new/deeper $FAST
refuse holds run plant -o . $FAST
refuse holds-abs run "$D/plant" -o "$D" $FAST
refuse holds-file run plant/bldA/01-ground.ini -o plant/bldA $FAST
refuse symlink run plant -o link $FAST
refuse symlink-inside run plant -o link/bldB $FAST
refuse symlink-operand run link -o plant $FAST
refuse dotdot run plant -o none/../plant $FAST
refuse dotdot-deep run plant -o plant/bldA/../../plant/bldB $FAST
refuse dotdot-abs run "$D/plant" -o "$D/plant/bldA/.." $FAST
WHERE=$D/plant refuse parent-of-cwd run . -o .. $FAST
WHERE=$D/plant/bldB refuse cwd-inside run ../../plant -o . $FAST
mkdir -p "$D/df/floors" && cp floors/01-ground.ini "$D/df/floors/"
WHERE=$D/df refuse default-floors run -o floors/new $FAST
refuse linked-floor run fl2 -o plant/bldA $FAST
refuse link-held run fl2/g.ini -o fl2 $FAST
mkdir -p "$D/ext/bldC" "$D/plant3/bldA" && cp floors/03-el24.ini "$D/ext/bldC/" && cp floors/01-ground.ini "$D/plant3/bldA/"
ln -s ../ext/bldC "$D/plant3/bldC"
refuse linked-building run plant3 -o ext/bldC/out $FAST
refuse linked-building-holds run plant3 -o ext $FAST
refuse cache-same run plant -o cc --cache cc $FAST
refuse cache-held run plant -o out0 --cache out0/c $FAST
refuse cache-inside run plant -o cc/out --cache cc $FAST
refuse synth-match synth --match rec/cms2.AT2 --rg160 0.3 -o rec
refuse synth-match-holds synth --match rec/cms2.AT2 --rg160 0.3 -o .
refuse synth-match-link synth --match m.AT2 --rg160 0.3 -o rec
refuse synth-floor synth --floor plant/bldA/01-ground.ini --count 1 --seed 1 -o plant
refuse slide-history slide --h1 rec/cms2.AT2 --mu 0.1 --history rec/cms2.AT2
refuse slide-history-link slide --h1 m.AT2 --mu 0.1 --history rec/cms2.AT2
refuse study-records study --records rec -o rec/out
[ ! -e "$D/none" ] && [ ! -e "$D/plant/bldA/new" ] && [ ! -e "$D/cc" ] && t_pass || t_fail "a refused -o made a folder"

# shards (their parent made, as mkdir -p), then merge -o among them: refused
t_run_in "$D" run plant --shard 1/2 -o parts/1 $FAST; t_expect_rc shard-1 0
t_run_in "$D" run plant --shard 2/2 -o parts/2 $FAST; t_expect_rc shard-2 0
ln -s parts/1 "$D/p1link"
refuse merge-same merge parts/1 parts/2 -o parts/1
refuse merge-holds merge parts/1 parts/2 -o parts
refuse merge-inside merge parts/1 parts/2 -o parts/2/results
refuse merge-link merge parts/1 parts/2 -o p1link
refuse merge-dotdot merge parts/1 parts/2 -o parts/1/../2
refuse merge-floors merge parts/1 parts/2 -o plant/bldA/..

# ---- a non-empty folder seislide did not make: exit 1, named, unchanged --------
mkdir "$D/mine" && echo "my floors" >"$D/mine/floors.csv" && echo "mine" >"$D/mine/summary.csv"
before=$(fp "$D/mine")
t_run_in "$D" run plant -o mine $FAST; t_expect_rc unmarked 1
t_expect_err unmarked-msg "mine: the output folder holds '(floors|summary)\.csv' and seislide did not make it"
[ "$(fp "$D/mine")" = "$before" ] && t_pass || t_fail "unmarked: the folder changed"
t_run_in "$D" merge parts/1 parts/2 -o mine; t_expect_rc unmarked-merge 1
t_run_in "$D" synth --rg160 0.3 --count 1 --seed 1 -q -o mine; t_expect_rc unmarked-synth 1
[ "$(fp "$D/mine")" = "$before" ] && t_pass || t_fail "unmarked (merge, synth): the folder changed"
ls -a "$D" | grep -Eq '\.lock$|\.tmp-' && t_fail "refusals left $(ls -a "$D" | grep -E 'lock|tmp')" || t_pass
# empty, or only .keep / .gitkeep (the repository's output/): accepted, the placeholder kept
mkdir "$D/empty" "$D/keep" && : >"$D/keep/.gitkeep" && : >"$D/keep/.keep"
t_run_in "$D" run plant -o empty $FAST; t_expect_rc empty 0
t_run_in "$D" run plant -o keep $FAST; t_expect_rc keep 0
[ -f "$D/keep/.gitkeep" ] && [ -f "$D/keep/.keep" ] && [ -f "$D/keep/plant.csv" ] && t_pass || t_fail "placeholders not kept"
grep -Eq '^\.(git)?keep$' "$D/keep/.seislide-manifest" && t_fail "the manifest names a placeholder" || t_pass

# ---- a rerun keeps what seislide did not write --------------------------------
O=$D/out
t_run_in "$D" run plant -o out $FAST; t_expect_rc first 0
[ "$(head -1 "$O/.seislide-manifest")" = "seislide-manifest 1" ] && t_pass || t_fail "manifest head: $(head -1 "$O/.seislide-manifest")"
for p in plant.csv plant.xlsx bldA/ bldA/summary.csv bldB/floors.csv .seislide-cache/; do
  grep -qxF "$p" "$O/.seislide-manifest" && t_pass || t_fail "the manifest does not name $p"
done
echo "my notes" >"$O/notes.txt"; chmod 600 "$O/notes.txt"
mkdir -p "$O/mine/deep" && echo "deep" >"$O/mine/deep/f.txt" && mkdir "$O/mine/empty"
echo "bldA note" >"$O/bldA/mynote.txt"
echo "bldB note" >"$O/bldB/keep.txt"
ln -s ../plant "$O/plantlink"
ino=$(stat -c %i "$O/notes.txt")
user() { (cd "$O" && fp . | grep -E 'notes|mine|mynote|keep\.txt|plantlink'); }
u0=$(user); xlsx0=$(sha256sum <"$O/plant.xlsx")
t_run_in "$D" run plant -o out --sets 2 --mu 0.1,0.3 --created 1700086400; t_expect_rc rerun 0
t_expect_err rerun-reused "reused 2 of 2 floors"
[ "$(user)" = "$u0" ] && t_pass || t_fail "rerun: the user's files changed: $(user)"
[ "$(stat -c %i "$O/notes.txt")" = "$ino" ] && t_pass || t_fail "rerun: notes.txt is another file"
[ "$(sha256sum <"$O/plant.xlsx")" != "$xlsx0" ] && t_pass || t_fail "rerun: the workbook was not replaced"
grep -Eq 'notes|mine|mynote|keep\.txt|plantlink' "$O/.seislide-manifest" && t_fail "the manifest names a user's file" || t_pass
# a rerun that no longer writes bldB: its outputs go, the user's file in it stays
mkdir -p "$D/plant2" && cp -r "$D/plant/bldA" "$D/plant2/"
t_run_in "$D" run plant2 -o out $FAST; t_expect_rc fewer 0
[ "$(ls -A "$O/bldB")" = "keep.txt" ] && t_pass || t_fail "bldB after a run without it: $(ls -A "$O/bldB")"
grep -q '^bldB' "$O/.seislide-manifest" && t_fail "the manifest still names bldB" || t_pass
[ "$(user)" = "$u0" ] && t_pass || t_fail "fewer: the user's files changed"
# a user's file where the run writes one: exit 1 naming it, the folder unchanged, the cache kept
echo "hand-made" >"$O/bldB/summary.csv"
before=$(fp "$O")
t_run_in "$D" run plant -o out $FAST; t_expect_rc conflict 1
t_expect_err conflict-msg "out/bldB/summary.csv: seislide did not write this"
[ "$(fp "$O")" = "$before" ] && t_pass || t_fail "conflict: the folder changed"
rm "$O/bldB/summary.csv"
t_run_in "$D" run plant -o out --sets 2 --mu 0.1,0.3 --created 1700000000; t_expect_rc after-conflict 0
t_expect_err after-conflict-reused "reused 2 of 2 floors"
[ "$(user)" = "$u0" ] && [ -f "$O/bldB/summary.csv" ] && t_pass || t_fail "after the conflict: outputs or user's files wrong"
# killed at the swap: DIR as it was, and the fresh folder already held the user's files
# (the same files: hard links), so that no moment of the swap can lose them
if command -v strace >/dev/null 2>&1 && strace -qq -o /dev/null true 2>/dev/null; then
  strace -f -qq -o /dev/null -e trace=renameat2 -e inject=renameat2:signal=SIGKILL:when=1 \
    "$B" run "$D/plant" -o "$O" $FAST 2>/dev/null
  fresh=$(ls -d "$D"/.out.tmp-* 2>/dev/null | head -1)
  [ -n "$fresh" ] && [ "$(stat -c %i "$fresh/notes.txt")" = "$ino" ] && [ -f "$fresh/mine/deep/f.txt" ] &&
    [ -L "$fresh/plantlink" ] && [ -d "$fresh/mine/empty" ] && t_pass || t_fail "killed at the swap: the fresh folder lacks the user's files"
  [ "$(user)" = "$u0" ] && t_pass || t_fail "killed at the swap: the user's files changed"
  t_run_in "$D" run plant -o out $FAST; t_expect_rc after-swap-kill 0
  ls -a "$D" | grep -q '^\.out\.tmp-' && t_fail "killed at the swap: its fresh folder stayed" || t_pass
else
  t_skip "strace absent or not allowed: the kill at the swap not tried"
fi
# synth and merge keep the user's files too
t_run_in "$D" synth --rg160 0.3 --count 1 --seed 1 -q -o syn; t_expect_rc synth 0
echo "mine" >"$D/syn/notes.txt"
t_run_in "$D" synth --rg160 0.3 --count 1 --seed 2 -q -o syn; t_expect_rc synth-again 0
[ "$(cat "$D/syn/notes.txt")" = mine ] && [ -f "$D/syn/set01_h1.AT2" ] && t_pass || t_fail "synth rerun lost the user's file"
t_run_in "$D" merge parts/1 parts/2 -q --created 1700000000 -o merged; t_expect_rc merge 0
echo "mine" >"$D/merged/notes.txt"
t_run_in "$D" merge parts/1 parts/2 -q --created 1700000000 -o merged; t_expect_rc merge-again 0
[ "$(cat "$D/merged/notes.txt")" = mine ] && same_csv "$D/merged" "$O" && t_pass || t_fail "merge rerun: user's file or outputs wrong"

# a manifest that is not one: an error naming its line, nothing changed
cp -a "$D/empty" "$D/bad1" && cp -a "$D/empty" "$D/bad2"
echo "../plant/bldA/01-ground.ini" >>"$D/bad1/.seislide-manifest"
n1=$(wc -l <"$D/bad1/.seislide-manifest")
sed -i '1s/.*/seislide-manifest 9/' "$D/bad2/.seislide-manifest"
before=$(fp "$D")
t_run_in "$D" run plant -o bad1 $FAST; t_expect_rc bad-manifest 1
t_expect_err bad-manifest-msg "bad1/\.seislide-manifest:$n1: '\.\./plant/bldA/01-ground\.ini' is not a path inside the folder"
t_run_in "$D" run plant -o bad2 $FAST; t_expect_rc bad-head 1
t_expect_err bad-head-msg "bad2/\.seislide-manifest:1: not a manifest seislide wrote"
[ "$(fp "$D")" = "$before" ] && t_pass || t_fail "a bad manifest: something changed"

# ---- missing parents are made ---------------------------------------------
t_run_in "$D" run plant -o deep/a/b/c $FAST; t_expect_rc parents 0
[ -f "$D/deep/a/b/c/plant.csv" ] && t_pass || t_fail "parents: no outputs"

# a swap killed between its two renames (file systems without RENAME_EXCHANGE) left
# no folder, the outputs aside: the next run puts them back, the user's file with them
host=$(hostname | tr -c 'A-Za-z0-9._\n-' _)
cp -a "$O" "$D/.gone.tmp-4194999@$host-abcdef"
t_run_in "$D" run plant -o gone --sets 2 --mu 0.1,0.3 --created 1700000000; t_expect_rc recover 0
t_expect_err recover-msg "put .gone.tmp-4194999@.* back in its place"
t_expect_err recover-reused "reused 2 of 2 floors"
[ "$(cat "$D/gone/notes.txt")" = "my notes" ] && same_csv "$D/gone" "$O" && t_pass || t_fail "recover: the user's file or the outputs"

# ---- two runs on one folder: the second refuses, naming the first ------------
"$B" run "$D/plant" -o "$D/conc" --sets 8 --mu 0.1,0.3 --created 1700000000 -q --cache "$D/cc8" & pa=$!
i=0; while [ $i -lt 2400 ] && ! grep -q '@' "$D/.conc.lock" 2>/dev/null; do sleep 0.05; i=$((i + 1)); done
t_run_in "$D" run plant -o ./conc/ $FAST; t_expect_rc busy 1
t_expect_err busy-msg "conc/: another run is writing this output folder: process $pa@[^ ]+ \(lock .*/\.conc\.lock\)"
wait $pa; ra=$?
[ $ra -eq 0 ] && t_pass || t_fail "the first run: exit $ra"
"$B" run "$D/plant" -o "$D/conc-ref" --sets 8 --mu 0.1,0.3 --created 1700000000 -q --cache "$D/cc8"
same_csv "$D/conc" "$D/conc-ref" && t_pass || t_fail "the folder does not hold the first run's outputs"
[ ! -e "$D/.conc.lock" ] && t_pass || t_fail "the lock stayed after the run"
t_run_in "$D" run plant -o conc $FAST; t_expect_rc after-busy 0
# a killed run's lock holds nothing
"$B" run "$D/plant" -o "$D/killed" --sets 8 --mu 0.1,0.3 -q --no-cache & pk=$!
i=0; while [ $i -lt 2400 ] && ! grep -q '@' "$D/.killed.lock" 2>/dev/null; do sleep 0.05; i=$((i + 1)); done
kill -9 $pk 2>/dev/null; wait $pk 2>/dev/null
t_run_in "$D" run plant -o killed $FAST; t_expect_rc after-kill 0
ls -a "$D" | grep -Eq '\.lock$|\.tmp-' && t_fail "left: $(ls -a "$D" | grep -E 'lock|tmp')" || t_pass

# ---- docs/plant.md's GNU parallel and Slurm lines, as written ----------------
mkdir -p "$T_TMP/bin" && ln -s "$B" "$T_TMP/bin/seislide"
P=$(sed -n 's/^    \(parallel seislide run plant --shard .*\)$/\1/p' docs/plant.md | head -1)
M=$(sed -n 's/^    \(seislide merge parts\/\* -o out\)$/\1/p' docs/plant.md | head -1)
S=$(sed -n '/^    #!\/bin\/sh$/,/^$/p' docs/plant.md | sed 's/^    //')
SM=$(sed -n 's/.*afterok:JOBID`), `\(seislide merge [^`]*\)`.*/\1/p' docs/plant.md | head -1)
[ -n "$P" ] && [ -n "$M" ] && [ -n "$S" ] && [ -n "$SM" ] && t_pass || t_fail "docs/plant.md: the shard lines not found"
export SOURCE_DATE_EPOCH=1700000000
if command -v parallel >/dev/null 2>&1; then
  mkdir "$D/gp" && cp -r "$D/plant" "$D/gp/"
  (cd "$D/gp" && PATH="$T_TMP/bin:$PATH" sh -c "$P" && PATH="$T_TMP/bin:$PATH" sh -c "$M") 2>"$T_TMP/gp.err"; r=$?
  [ $r -eq 0 ] && [ -f "$D/gp/out/plant.csv" ] && t_pass || t_fail "docs: GNU parallel + merge: exit $r: $(head -c 300 "$T_TMP/gp.err")"
else
  t_skip "GNU parallel absent: its docs line not run"
fi
# the Slurm array: the job script as written, once per task, all at once
mkdir "$D/sl" && cp -r "$D/plant" "$D/sl/" && printf '%s\n' "$S" >"$D/sl/job.sh"
pids=""
for k in $(seq 16); do
  (cd "$D/sl" && SLURM_ARRAY_TASK_ID=$k SLURM_CPUS_PER_TASK=1 PATH="$T_TMP/bin:$PATH" sh job.sh) 2>"$D/sl.$k.err" & pids="$pids $!"
done
bad=0; for p in $pids; do wait $p || bad=$((bad + 1)); done
[ $bad -eq 0 ] && t_pass || t_fail "docs: Slurm tasks: $bad of 16 failed: $(cat "$D"/sl.*.err | head -c 300)"
(cd "$D/sl" && PATH="$T_TMP/bin:$PATH" sh -c "$SM") 2>"$T_TMP/sl.err"; r=$?
[ $r -eq 0 ] && [ -f "$D/sl/out/plant.csv" ] && t_pass || t_fail "docs: Slurm merge: exit $r: $(head -c 300 "$T_TMP/sl.err")"
if [ -d "$D/gp/out" ]; then
  same_csv "$D/sl/out" "$D/gp/out" && t_pass || t_fail "docs: 16 Slurm shards and 3 parallel shards merge to different data"
fi
unset SOURCE_DATE_EPOCH

t_end
