#!/bin/sh
# Output folders that are not a plain new folder (issue 39 A, docs/reliability.md,
# "Output folders of every kind"): `-o DIR/.` and `-o .` from inside the folder; a user's
# folder nested 100 deep inside it, and one deeper than a path may be; a file system
# mounted inside it (refused before any work, the mount kept), and the folder itself a
# mount point (written in place; also in a read-only parent, and a volume's root holding
# lost+found); the swap refused (EBUSY,
# EXDEV: everything back, the cache included); `-o` a symbolic link (followed, by every
# command; a dangling one refused); a user's save between the carry and the swap; a
# write-protected folder. After each: the whole tree's checksums (every path, type,
# mode, link target and file byte) where nothing may change, every user's byte where
# the run succeeds, and no exit status of a crash (>= 128). The mount cases run in
# `unshare -m` as root; skipped with a message where that is not allowed.
. "$(dirname "$0")/lib.sh"
t_suite cli_outdirs
D=$T_TMP/w; mkdir "$D"
B=$(cd "$(dirname "$SEISLIDE_BIN")" && pwd)/$(basename "$SEISLIDE_BIN")
OMP_NUM_THREADS=1; export OMP_NUM_THREADS
# LeakSanitizer cannot run under ptrace: the traced runs of `make asan` skip it
NOLEAK="env ASAN_OPTIONS=detect_leaks=0"
FAST="--sets 2 --mu 0.1,0.3 --created 1700000000 -q"
cp floors/01-ground.ini "$D/g.ini"
G=$D/g.ini

# fp TREE: every path with its type and mode, link target or file checksum (any depth)
cat >"$D/fp.py" <<'PY'
import hashlib, os, stat, sys
sys.setrecursionlimit(100000)
root, out = sys.argv[1], []
if os.path.lexists(root):
    for dp, ds, fs, dfd in os.fwalk(root, follow_symlinks=False):
        rel = os.path.relpath(dp, root)
        for n in ds + fs:
            st = os.stat(n, dir_fd=dfd, follow_symlinks=False)
            if stat.S_ISLNK(st.st_mode):
                what = os.readlink(n, dir_fd=dfd)
            elif stat.S_ISREG(st.st_mode):
                fd, h = os.open(n, os.O_RDONLY, dir_fd=dfd), hashlib.sha256()
                while True:
                    b = os.read(fd, 1 << 16)
                    if not b:
                        break
                    h.update(b)
                os.close(fd)
                what = h.hexdigest()
            else:
                what = ''
            out.append('%s %o %s' % (os.path.join(rel, n), st.st_mode, what))
print('\n'.join(sorted(out)))
PY
fp() { python3 "$D/fp.py" "$1"; }
# the user's entries of an output folder (not what its manifest names, not seislide's own)
user_fp() { fp "$1" | grep -Ev '^\./(\.seislide|asce_|floor|motion_|summary|seislide-clearance|set[0-9])'; }
# t_cmd_in DIR NAME RC CMD...: CMD from folder DIR, exit RC expected, never a crash
t_cmd_in() {
  d=$1; name=$2; want=$3; shift 3
  T_OUT=$T_TMP/out; T_ERR=$T_TMP/err
  (cd "$d" && "$@") >"$T_OUT" 2>"$T_ERR"; T_RC=$?
  [ "$T_RC" -lt 128 ] && t_pass || t_fail "$name: exit $T_RC (a crash): $(head -c 300 "$T_ERR")"
  t_expect_rc "$name" "$want"
}
# t_run_in DIR NAME RC ARGS: seislide ARGS so
t_run_in() { d=$1; name=$2; want=$3; shift 3; t_cmd_in "$d" "$name" "$want" "$B" "$@"; }
# nothing beside or inside DIR that a run leaves (fresh folders, locks, temporaries)
clean_around() { ! ls -A "$(dirname "$1")" "$1" 2>/dev/null | grep -Eq '\.tmp-|\.lock$|^\.seislide\.'; }

# ---- 1. -o DIR/. and -o . from inside an output folder -------------------------------
t_run_in "$D" dot-new 0 run "$G" $FAST -o new/.
[ -f "$D/new/floors.csv" ] && [ ! -e "$D/new/new" ] && clean_around "$D/new" && t_pass ||
  t_fail "-o new/.: $(ls -A "$D" "$D/new" | tr '\n' ' ')"
echo "my notes" >"$D/new/notes.txt"; mkdir -p "$D/new/mine/sub" && echo x >"$D/new/mine/sub/x.txt"
u0=$(user_fp "$D/new")
t_run_in "$D" dot-again 0 run "$G" $FAST -o new/.
t_run_in "$D/new" dot-inside 0 run "$G" $FAST -o .
t_run_in "$D/new" dot-slash-inside 0 run "$G" $FAST -o ./
t_run_in "$D/new/mine" dotdot-inside 0 run "$G" $FAST -o ..
t_expect_err dotdot-note "the current folder was inside the output folder"
t_run_in "$D/new/mine/sub" dotdot-deep-inside 0 run "$G" $FAST -o ../../.
[ "$(user_fp "$D/new")" = "$u0" ] && clean_around "$D/new" && t_pass || t_fail "-o . from inside: the user's files changed"
t_run_in "$D" synth-dot 0 synth --rg160 0.3 --count 1 --seed 1 -q -o syn/.
t_run_in "$D/syn" synth-dot-inside 0 synth --rg160 0.3 --count 1 --seed 2 -q -o .
[ -f "$D/syn/set01_h1.AT2" ] && [ ! -e "$D/syn/syn" ] && clean_around "$D/syn" && t_pass || t_fail "synth -o .: $(ls -A "$D/syn")"

# ---- 2. a user's folder nested deep inside the output folder ----------------------------
# deep DIR N NAME: a chain of N folders NAME under DIR, a file at its end
deep() {
  python3 - "$1" "$2" "$3" <<'PY'
import os, sys
fd = os.open(sys.argv[1], os.O_RDONLY)
for i in range(int(sys.argv[2])):
    os.mkdir(sys.argv[3], dir_fd=fd)
    n = os.open(sys.argv[3], os.O_RDONLY, dir_fd=fd); os.close(fd); fd = n
f = os.open('end.txt', os.O_WRONLY | os.O_CREAT, 0o644, dir_fd=fd)
os.write(f, b'the end'); os.close(f)
PY
}
t_run_in "$D" deep-first 0 run "$G" $FAST -o dp
mkdir "$D/dp/nest" && deep "$D/dp/nest" 100 d
u0=$(user_fp "$D/dp")
t_run_in "$D" deep-100 0 run "$G" $FAST -o dp
t_run_in "$D" deep-100-again 0 run "$G" $FAST -o dp
[ "$(user_fp "$D/dp")" = "$u0" ] && clean_around "$D/dp" && t_pass || t_fail "100 deep: the user's folder changed"
# deeper than a path may be (1500 x 3 characters > 4096): exit 1 naming it, nothing changed
mkdir "$D/dp/nest2" && deep "$D/dp/nest2" 1500 dd
before=$(fp "$D")
t_run_in "$D" deep-1500 1 run "$G" $FAST -o dp
t_expect_err deep-1500-msg "dp/nest2/dd/dd.*File name too long; the output folder is unchanged \(a folder nested deeper"
[ "$(fp "$D")" = "$before" ] && t_pass || t_fail "1500 deep: something changed"
rm -rf "$D/dp/nest2"

# ---- 5. the swap refused: everything back, the cache included ----------------------------
if command -v strace >/dev/null 2>&1 && strace -qq -o /dev/null true 2>/dev/null; then
  t_run_in "$D" busy-first 0 run "$G" $FAST -o busy
  echo "mine" >"$D/busy/notes.txt"
  for e in EBUSY EXDEV EACCES ENOSPC; do
    before=$(fp "$D")
    t_cmd_in "$D" "swap-$e" 1 $NOLEAK strace -f -qq -o /dev/null -e trace=renameat2 \
      -e inject=renameat2:error=$e:when=1 "$B" run "$G" --sets 2 --mu 0.1,0.3 --created 1700086400 -q -o busy
    t_expect_err "swap-$e-msg" "cannot replace: .*; the output folder is unchanged"
    [ "$(fp "$D")" = "$before" ] && t_pass || t_fail "swap refused ($e): something changed, the cache $(ls "$D/busy/.seislide-cache" 2>&1 | head -c 100)"
  done
  # ---- 7. a file saved between the carry and the swap (the swap held 1.5 s) ---------------
  "$B" run "$G" --sets 2 --mu 0.1,0.3 --created 1700086400 -q -o "$D/busy" 2>/dev/null
  $NOLEAK strace -f -qq -o /dev/null -e trace=renameat2 -e inject=renameat2:delay_enter=1500000:when=1 \
    "$B" run "$G" $FAST -o "$D/busy" 2>"$T_TMP/save.err" & pid=$!
  i=0; while [ $i -lt 600 ] && [ -z "$(ls "$D"/.busy.tmp-*/notes.txt 2>/dev/null)" ]; do sleep 0.02; i=$((i + 1)); done
  printf 'edited' >"$D/busy/notes.txt.swp" && mv "$D/busy/notes.txt.swp" "$D/busy/notes.txt"
  echo "added" >"$D/busy/added.txt"
  wait $pid; rc=$?
  [ $rc -eq 0 ] && [ "$(cat "$D/busy/notes.txt")" = edited ] && [ "$(cat "$D/busy/added.txt")" = added ] &&
    clean_around "$D/busy" && t_pass || t_fail "saved while the run finished: exit $rc, notes '$(cat "$D/busy/notes.txt")', $(cat "$T_TMP/save.err")"
else
  t_skip "strace absent or not allowed: the refused swap and the save at the swap not tried"
fi

# ---- 6. -o a symbolic link: followed by every command, the link kept ----------------------
mkdir "$D/real"
ln -s real "$D/link"
t_run_in "$D" link-run 0 run "$G" $FAST -o link
t_run_in "$D" link-run-again 0 run "$G" --sets 2 --mu 0.1,0.3 --created 1700000000 -o link
t_expect_err link-reused "reused 1 of 1 floors"
t_run_in "$D" link-real 0 run "$G" --sets 2 --mu 0.1,0.3 --created 1700000000 -o real/
t_expect_err link-real-reused "reused 1 of 1 floors"
[ -L "$D/link" ] && [ -f "$D/real/floors.csv" ] && [ -d "$D/real/.seislide-cache" ] && clean_around "$D/real" &&
  t_pass || t_fail "-o link: $(ls -lA "$D" | tr '\n' ' ')"
mkdir "$D/sreal" && ln -s sreal "$D/slink"
t_run_in "$D" link-synth 0 synth --rg160 0.3 --count 1 --seed 1 -q -o slink
[ -L "$D/slink" ] && [ -f "$D/sreal/set01_h1.AT2" ] && t_pass || t_fail "synth -o link"
ln -s nowhere "$D/dangling"
before=$(fp "$D")
t_run_in "$D" link-dangling 1 run "$G" $FAST -o dangling
t_expect_err link-dangling-msg "dangling: the output folder is a symbolic link to 'nowhere', which does not exist"
t_run_in "$D" link-dangling-synth 1 synth --rg160 0.3 --count 1 --seed 1 -q -o dangling
[ "$(fp "$D")" = "$before" ] && t_pass || t_fail "a dangling link: something changed"

# ---- 8. a write-protected folder: refused, naming it ---------------------------------
t_run_in "$D" ro-first 0 run "$G" $FAST -o ro
chmod 555 "$D/ro"
before=$(fp "$D")
t_run_in "$D" ro-nocache 1 run "$G" $FAST --no-cache -o ro
t_expect_err ro-msg "ro: the output folder is write-protected \(mode 0555\)"
t_run_in "$D" ro-cache 1 run "$G" $FAST -o ro
t_run_in "$D" ro-synth 1 synth --rg160 0.3 --count 1 --seed 1 -q -o ro
[ "$(fp "$D")" = "$before" ] && t_pass || t_fail "a write-protected folder: something changed"
if [ "$(id -u)" -eq 0 ] && command -v setpriv >/dev/null 2>&1; then
  mkdir "$D/nb" && chmod 777 "$D/nb" && cp "$G" "$D/nb/g.ini" && chmod 711 "$T_TMP" "$D"
  setpriv --reuid=nobody --regid=nogroup --clear-groups "$B" run "$D/nb/g.ini" $FAST -o "$D/nb/out" 2>/dev/null
  chmod 555 "$D/nb/out"; before=$(fp "$D/nb")
  setpriv --reuid=nobody --regid=nogroup --clear-groups "$B" run "$D/nb/g.ini" $FAST --no-cache -o "$D/nb/out" 2>"$T_TMP/nb.err"; rc=$?
  [ $rc -eq 1 ] && grep -q "write-protected (Permission denied)" "$T_TMP/nb.err" && [ "$(fp "$D/nb")" = "$before" ] &&
    t_pass || t_fail "as nobody: exit $rc: $(cat "$T_TMP/nb.err")"
else
  t_skip "not root or no setpriv: a write-protected folder not tried as another user"
fi
chmod 755 "$D/ro"

# ---- 3, 4. mounts, in their own mount namespace ---------------------------------------
if [ "$(id -u)" -eq 0 ] && command -v unshare >/dev/null 2>&1 && unshare -m true 2>/dev/null; then
  R=$T_TMP/results; : >"$R"
  cat >"$T_TMP/mounts.sh" <<'EOF'
# run by test_outdirs.sh in `unshare -m`: one line per check into $R: P, F MESSAGE
D=$1; R=$2; B=$3; G=$4; FAST=$5
ok() { echo P >>"$R"; }
bad() { echo "F $*" >>"$R"; }
rc_is() { [ "$1" -lt 128 ] && [ "$1" -eq "$2" ] && ok || bad "$3: exit $1, expected $2: $(head -c 300 "$D/m.err")"; }
fp_of() { python3 "$D/fp.py" "$1"; }
M=$D/mnt; mkdir -p "$M"
# 3. a tmpfs inside the output folder, holding a user's files: refused before any work
"$B" run "$G" $FAST -o "$M/in" 2>"$D/m.err"; rc_is $? 0 "first run"
mkdir "$M/in/data" && mount -t tmpfs tmpfs "$M/in/data" && echo "on the mount" >"$M/in/data/f.txt"
before=$(fp_of "$M")
"$B" run "$G" $FAST -o "$M/in" 2>"$D/m.err"; rc_is $? 1 "a mount inside"
grep -q "in: a file system is mounted at .*/in/data, inside the output folder" "$D/m.err" && ok || bad "mount inside: $(cat "$D/m.err")"
"$B" run "$G" $FAST --no-cache -o "$M/in" 2>"$D/m.err"; rc_is $? 1 "a mount inside, --no-cache"
"$B" synth --rg160 0.3 --count 1 --seed 1 -q -o "$M/in" 2>"$D/m.err"; rc_is $? 1 "a mount inside, synth"
[ "$(fp_of "$M")" = "$before" ] && mountpoint -q "$M/in/data" && ok || bad "a mount inside: changed or unmounted"
# the same with a bind mount of a folder of the same file system (the same device)
umount "$M/in/data"; mkdir -p "$D/elsewhere" && echo "bound" >"$D/elsewhere/b.txt"
mount --bind "$D/elsewhere" "$M/in/data"
before=$(fp_of "$M")
"$B" run "$G" $FAST -o "$M/in" 2>"$D/m.err"; rc_is $? 1 "a bind mount inside"
[ "$(fp_of "$M")" = "$before" ] && [ "$(cat "$D/elsewhere/b.txt")" = bound ] && ok || bad "a bind mount inside: changed"
umount "$M/in/data"
# 4. the output folder a mount point (a container's -v host:/out): written in place
mkdir "$M/out" && mount -t tmpfs tmpfs "$M/out"
"$B" run "$G" $FAST -o "$M/out" 2>"$D/m.err"; rc_is $? 0 "a mount point, first run"
echo "my notes" >"$M/out/notes.txt"; ino=$(stat -c %i "$M/out/notes.txt")
mkdir -p "$M/out/mine/deep" && echo deep >"$M/out/mine/deep/f.txt"
"$B" run "$G" --sets 2 --mu 0.1,0.3 --created 1700086400 -o "$M/out" 2>"$D/m.err"; rc_is $? 0 "a mount point, rerun"
grep -q "reused 1 of 1 floors" "$D/m.err" && ok || bad "a mount point: the cache not reused: $(cat "$D/m.err")"
[ "$(stat -c %i "$M/out/notes.txt")" = "$ino" ] && [ "$(cat "$M/out/mine/deep/f.txt")" = deep ] &&
  [ -d "$M/out/.seislide-cache" ] && ! ls -A "$M/out" | grep -q '^\.seislide\.' && ok ||
  bad "a mount point, rerun: $(ls -A "$M/out" | tr '\n' ' ')"
"$B" run "$G" $FAST --no-cache -o "$M/out" 2>"$D/m.err"; rc_is $? 0 "a mount point, --no-cache"
umount "$M/out"; mount -t tmpfs tmpfs "$M/out"
"$B" synth --rg160 0.3 --count 1 --seed 1 -q -o "$M/out" 2>"$D/m.err"; rc_is $? 0 "a mount point, synth"
"$B" synth --rg160 0.3 --count 1 --seed 2 -q -o "$M/out" 2>"$D/m.err"; rc_is $? 0 "a mount point, synth again"
umount "$M/out"; mount -t tmpfs tmpfs "$M/out"
"$B" run "$G" $FAST -o "$M/out" 2>"$D/m.err"; rc_is $? 0 "a mount point, first run"
echo "my notes" >"$M/out/notes.txt"
# an exchange refused part-way (the 1st, the 3rd): everything back, the cache included
for n in 1 3; do
  if command -v strace >/dev/null 2>&1; then
    before=$(fp_of "$M/out")
    env ASAN_OPTIONS=detect_leaks=0 strace -f -qq -o /dev/null -e trace=renameat2 -e inject=renameat2:error=EBUSY:when=$n \
      "$B" run "$G" --sets 2 --mu 0.1,0.3 --created 1700086400 -q -o "$M/out" 2>"$D/m.err"; rc_is $? 1 "in place, exchange $n refused"
    [ "$(fp_of "$M/out")" = "$before" ] && ok || bad "in place, exchange $n refused: changed: $(cat "$D/m.err")"
  fi
done
# a volume's root (lost+found, the file system's own): accepted and kept
mkdir "$M/vol" && mount -t tmpfs tmpfs "$M/vol" && mkdir "$M/vol/lost+found" && chmod 700 "$M/vol/lost+found"
"$B" run "$G" $FAST -o "$M/vol" 2>"$D/m.err"; rc_is $? 0 "a volume with lost+found"
"$B" run "$G" $FAST -o "$M/vol" 2>"$D/m.err"; rc_is $? 0 "a volume with lost+found, rerun"
[ -d "$M/vol/lost+found" ] && [ -f "$M/vol/floors.csv" ] && ok || bad "lost+found: $(ls -A "$M/vol" | tr '\n' ' ')"
# a mount point in a read-only parent: the lock inside, written in place
mkdir "$M/ro" && mount -t tmpfs tmpfs "$M/ro" && mkdir "$M/ro/out" && mount -t tmpfs tmpfs "$M/ro/out"
mount -o remount,ro "$M/ro"
"$B" run "$G" $FAST -o "$M/ro/out" 2>"$D/m.err"; rc_is $? 0 "a mount point in a read-only parent"
echo "note" >"$M/ro/out/n.txt"
"$B" run "$G" $FAST -o "$M/ro/out" 2>"$D/m.err"; rc_is $? 0 "a mount point in a read-only parent, rerun"
[ "$(cat "$M/ro/out/n.txt")" = note ] && [ -f "$M/ro/out/floors.csv" ] && ! ls -A "$M/ro/out" | grep -q '^\.seislide\.' && ok ||
  bad "read-only parent: $(ls -A "$M/ro/out" | tr '\n' ' ')"
# a read-only mount as the output folder: refused, naming it
mount -o remount,ro "$M/ro/out"
"$B" run "$G" $FAST -o "$M/ro/out" 2>"$D/m.err"; rc_is $? 1 "a read-only mount"
grep -q "write-protected (Read-only file system)" "$D/m.err" && ok || bad "a read-only mount: $(cat "$D/m.err")"
EOF
  if unshare -m sh "$T_TMP/mounts.sh" "$D" "$R" "$B" "$G" "$FAST" 2>"$T_TMP/mounts.err"; then :; fi
  [ -s "$R" ] || t_fail "the mount checks printed nothing: $(head -c 300 "$T_TMP/mounts.err")"
  while read -r what msg; do
    case $what in P) t_pass ;; *) t_fail "$msg" ;; esac
  done <"$R"
else
  t_skip "not root, or unshare -m not allowed: the mount cases (a mount inside -o, -o a mount point) not tried"
fi

t_end
