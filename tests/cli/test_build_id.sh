#!/bin/sh
# The build's identity (src/core/version.h; docs/reliability.md, "Which code made a
# number"; issue 39): the fingerprint of the sources is the same for a copy of the
# tree, another when one constant of one source changes, the same again when it is
# put back; the program prints it (--version, the program line of the CSV files and
# the workbook). Two builds that differ in one result-changing constant, one cache:
# the second recomputes, its numbers differ, and the first still reuses its own
# entry. The second build is a scratch copy of the tree with this build's objects,
# one source changed, only the program rebuilt (seconds).
. "$(dirname "$0")/lib.sh"
t_suite cli_build_id
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
D=$T_TMP
B=build
for v in $SEISLIDE_MAKEVARS; do case $v in BUILD=*) B=${v#BUILD=} ;; esac; done
FAST="--sets 2 --mu 0.2,0.4 --created 1700000000"

id0=$(make -s --no-print-directory -C "$ROOT" source-id $SEISLIDE_MAKEVARS 2>/dev/null)
echo "$id0" | grep -Eqx '[0-9a-f]{64}' && t_pass || t_fail "make source-id: '$id0'"
short0=$(echo "$id0" | cut -c1-12)
V=$(sed -n 's/^#define SEISLIDE_VERSION_[A-Z]* \([0-9][0-9]*\)$/\1/p' "$ROOT/src/core/version.h" | paste -sd.)
[ "$("$SEISLIDE_BIN" --version)" = "seislide $V (source $short0)" ] && t_pass ||
  t_fail "--version: '$("$SEISLIDE_BIN" --version)', expected 'seislide $V (source $short0)' (is the program built from these sources?)"

# a scratch copy of the tree and of this build's objects (timestamps kept)
T=$D/tree
mkdir -p "$T/tests/fuzz" "$T/$B"
cp -p "$ROOT/Makefile" "$T/" && cp -pR "$ROOT/src" "$T/" && cp -p "$ROOT/tests/fuzz/fuzz.mk" "$T/tests/fuzz/" &&
  cp -pR "$ROOT/$B/src" "$T/$B/" && cp -p "$ROOT/$B"/*.a "$ROOT/$B/source_id.h" "$T/$B/" && t_pass || t_fail "scratch copy"
[ "$(make -s --no-print-directory -C "$T" source-id)" = "$id0" ] && t_pass || t_fail "a copy of the tree has another fingerprint"
# one result-changing constant: the NLTHA design value 1.25 x larger (method/design.c)
sed -i 's/double dn = in->fs_nltha \* r->nltha_mean_m;/double dn = 1.25 * in->fs_nltha * r->nltha_mean_m;/' "$T/src/method/design.c"
grep -q 'dn = 1.25 \* in->fs_nltha' "$T/src/method/design.c" && t_pass || t_fail "the constant was not changed (design.c moved on?)"
id1=$(make -s --no-print-directory -C "$T" source-id)
[ -n "$id1" ] && [ "$id1" != "$id0" ] && t_pass || t_fail "one changed constant kept the fingerprint $id0"
# shellcheck disable=SC2086
make -s --no-print-directory -C "$T" $SEISLIDE_MAKEVARS LDFLAGS="$SEISLIDE_LDFLAGS" PROG=seislide-b seislide-b >"$D/make.out" 2>&1
[ $? -eq 0 ] && [ -x "$T/seislide-b" ] && t_pass || t_fail "second build: $(head -c 600 "$D/make.out")"
short1=$(echo "$id1" | cut -c1-12)
[ "$("$T/seislide-b" --version)" = "seislide $V (source $short1)" ] && t_pass ||
  t_fail "second build's --version: '$("$T/seislide-b" --version)'"

# one cache, two builds
run_with() { # PROG OUT
  "$1" run floors/01-ground.ini $FAST --cache "$D/cache" -o "$2" >/dev/null 2>"$D/err.$(basename "$2")"
}
run_with "$SEISLIDE_BIN" "$D/a" && grep -q "reused 0 of 1 floors" "$D/err.a" && t_pass || t_fail "first build: $(tail -c 300 "$D/err.a")"
run_with "$SEISLIDE_BIN" "$D/a2" && grep -q "reused 1 of 1 floors" "$D/err.a2" && t_pass || t_fail "first build again: $(tail -c 300 "$D/err.a2")"
run_with "$T/seislide-b" "$D/b" && grep -q "reused 0 of 1 floors" "$D/err.b" && t_pass ||
  t_fail "the second build was served the first's result: $(grep reused "$D/err.b")"
data() { grep -v '^#' "$1/floor_01-ground.csv"; }
[ "$(data "$D/a")" = "$(data "$D/a2")" ] && t_pass || t_fail "the reused result differs from the computed one"
[ "$(data "$D/a")" != "$(data "$D/b")" ] && t_pass || t_fail "the changed constant changed no number"
run_with "$SEISLIDE_BIN" "$D/a3" && grep -q "reused 1 of 1 floors" "$D/err.a3" && [ "$(data "$D/a")" = "$(data "$D/a3")" ] &&
  t_pass || t_fail "the first build lost its own entry: $(grep reused "$D/err.a3")"
# each output names the build behind its numbers
for f in floors.csv floor_01-ground.csv summary.csv; do
  tr -d "\r" <"$D/a/$f" | grep -qx "# program: seislide $V (source $short0)" && tr -d "\r" <"$D/b/$f" | grep -qx "# program: seislide $V (source $short1)" &&
    t_pass || t_fail "$f: program lines '$(grep '^# program' "$D/a/$f")' and '$(grep '^# program' "$D/b/$f")'"
done
if command -v unzip >/dev/null 2>&1; then
  unzip -p "$D/b/seislide-clearance.xlsx" xl/sharedStrings.xml | grep -q "seislide $V (source $short1)" && t_pass ||
    t_fail "the workbook does not name the second build"
else
  t_skip "unzip not installed: the workbook's program line is not read"
fi

# the constant put back: the first fingerprint again
sed -i 's/double dn = 1.25 \* in->fs_nltha/double dn = in->fs_nltha/' "$T/src/method/design.c"
[ "$(make -s --no-print-directory -C "$T" source-id)" = "$id0" ] && t_pass || t_fail "the restored tree has another fingerprint"
t_end
