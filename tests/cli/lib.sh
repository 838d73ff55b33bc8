# lib.sh - helpers for end-to-end tests of the seislide command line.
# Source it, call `t_begin NAME`, then `t_ok`/`t_fail MSG` per check, `t_end`.
: "${SEISLIDE_BIN:=./seislide}"
: "${SEISLIDE_SHARED:=../shared}"
T_PASS=0; T_FAIL=0; T_SKIP=0; T_SUITE=cli
T_TMP=$(mktemp -d) || exit 2
trap 'rm -rf "$T_TMP"' EXIT
t_suite() { T_SUITE=$1; }
t_pass() { T_PASS=$((T_PASS + 1)); }
t_fail() { T_FAIL=$((T_FAIL + 1)); echo "  FAIL $T_SUITE: $*" >&2; }
t_skip() { T_SKIP=$((T_SKIP + 1)); echo "  SKIP $T_SUITE: $*" >&2; }
# t_run: run seislide with args; sets T_RC, T_OUT (stdout file), T_ERR (stderr file)
t_run() {
  T_OUT=$T_TMP/out; T_ERR=$T_TMP/err
  "$SEISLIDE_BIN" "$@" >"$T_OUT" 2>"$T_ERR"; T_RC=$?
}
# t_expect_rc NAME RC: check last exit code
t_expect_rc() { if [ "$T_RC" -eq "$2" ]; then t_pass; else t_fail "$1: exit $T_RC, expected $2 ($(head -c 300 "$T_ERR"))"; fi; }
# t_expect_err NAME REGEX: stderr matches (grep -E)
t_expect_err() { if grep -Eq -- "$2" "$T_ERR"; then t_pass; else t_fail "$1: stderr '$(head -c 300 "$T_ERR")' does not match /$2/"; fi; }
t_expect_out() { if grep -Eq -- "$2" "$T_OUT"; then t_pass; else t_fail "$1: stdout '$(head -c 300 "$T_OUT")' does not match /$2/"; fi; }
t_end() { echo "$T_SUITE: $T_PASS passed, $T_FAIL failed, $T_SKIP skipped"; [ "$T_FAIL" -eq 0 ]; }
