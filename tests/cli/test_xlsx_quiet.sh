#!/bin/sh
# libxlsxwriter prints its own "[ERROR] ..." lines on stderr when it cannot write a
# workbook (a file size limit, a full disk); the library prints nothing (issue 39):
# report/workbook.c holds the standard error while libxlsxwriter writes. Under a file
# size limit (EFBIG) and on a full tmpfs (ENOSPC, in a mount namespace of its own, as
# root; skipped where that is not permitted), `run` and `components` end with exit 1
# and seislide's one line naming the workbook and the system's reason, no line of
# libxlsxwriter's, nothing left behind.
. "$(dirname "$0")/lib.sh"
t_suite cli_xlsx_quiet
D=$T_TMP
FAST="--sets 2 --mu 0.2,0.4 --created 1700000000"
# only seislide's own line: one line, "seislide: FILE: cannot write the workbook: REASON (...)"
only_ours() { # NAME FILE REASON
  if [ "$(wc -l < "$T_ERR")" -eq 1 ] && ! grep -q '\[ERROR\]\|\[WARNING\]' "$T_ERR" &&
     grep -Eq "^seislide: .*$2: cannot write the workbook: $3 \(libxlsxwriter: " "$T_ERR"; then t_pass
  else t_fail "$1: stderr is not seislide's one line: $(head -c 600 "$T_ERR")"; fi
}

# the results a components run reads (no limit)
t_run run floors/01-ground.ini -o "$D/res" $FAST -q; t_expect_rc results 0
printf 'tag,building,floor,mu,base_m,cg_height_m,clearance_mm\nP1,,01-ground,0.3,1,1,100\n' > "$D/list.csv"

# ---- a file size limit (ulimit -f counts 512-byte blocks in POSIX shells; measured)
sh -c 'ulimit -f 4; head -c 8192 /dev/zero > "$1"; :' sh "$D/probe" 2>/dev/null
BLK=$(($(wc -c < "$D/probe") / 4))
limited() { # BYTES ARGS...: run seislide under a file size limit
  lim=$(($1 / BLK)); shift
  (ulimit -f $lim; exec "$SEISLIDE_BIN" "$@" > "$T_OUT" 2> "$T_ERR"); T_RC=$?
}
T_OUT=$D/out; T_ERR=$D/err
# the CSV files (< 2 kB) fit, the workbook (23 kB) does not
limited 12288 run floors/01-ground.ini -o "$D/lim" $FAST -q --no-cache; t_expect_rc fsize-run 1
only_ours fsize-run "lim/seislide-clearance.xlsx" "File too large"
[ ! -e "$D/lim" ] && t_pass || t_fail "fsize-run: output folder left: $(ls -a "$D/lim")"
limited 12288 components "$D/res" "$D/list.csv" -o "$D/climb" --created 1700000000
t_expect_rc fsize-components 1
only_ours fsize-components "climb/components.xlsx" "File too large"

# ---- a full disk: a 40 kB tmpfs (10 pages) holds the output folder: the CSV files
# (a page each) fit, the workbook does not
if [ "$(id -u)" -eq 0 ] && command -v unshare >/dev/null 2>&1 &&
   unshare -m sh -c 'mount -t tmpfs -o size=4k tmpfs "$1" && umount "$1"' sh "$D" 2>/dev/null; then
  mkdir -p "$D/full"
  unshare -m sh -c 'mount -t tmpfs -o size=40k tmpfs "$1" && exec "$2" run floors/01-ground.ini -o "$1/r" $3 -q --no-cache' \
    sh "$D/full" "$SEISLIDE_BIN" "$FAST" > "$T_OUT" 2> "$T_ERR"; T_RC=$?
  t_expect_rc enospc-run 1
  only_ours enospc-run "full/r/seislide-clearance.xlsx" "No space left on device"
else
  t_skip "no mount namespace (needs root and unshare -m): the full-disk case is not run"
fi
t_end
