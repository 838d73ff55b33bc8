#!/bin/sh
# End-to-end tests of `seislide components` and `run --components`
# (docs/components.md): 40 components of a plant recomputed from the floor
# CSVs by this script's own code (interpolation, Shenton's b/h bound,
# margins) and compared verdict by verdict; rows added to the Components
# sheet and recalculated by LibreOffice against components.csv; every
# malformed row refused naming its line, with nothing written; the
# workbook rendered to PDF and read.
. "$(dirname "$0")/lib.sh"
t_suite cli_components
D=$T_TMP
B="$SEISLIDE_BIN"
if ! command -v python3 >/dev/null 2>&1; then
  t_skip "python3 absent: the components are not recomputed"; t_end; exit $?
fi
mkdir -p "$D/plant/bldA" "$D/plant/bld-B" "$D/one"
cp floors/01-ground.ini floors/02-el12.ini "$D/plant/bldA/"
cp floors/03-el24.ini floors/04-roof36.ini "$D/plant/bld-B/"
cp floors/01-ground.ini floors/04-roof36.ini "$D/one/"
OPTS="--sets 2 --mu 0.05,0.1,0.2,0.3,0.5 --created 1700000000 -q --no-cache"
t_run run "$D/plant" -o "$D/res" $OPTS; t_expect_rc plant-run 0
t_run run "$D/one" -o "$D/res1" $OPTS; t_expect_rc one-building-run 0

# the component lists: A (given to the command) and B (typed into the
# workbook later); mu on grid points, between them, below and above the
# grid; slender and squat bodies; gaps from 0 to 900 mm; floors by id and
# by name in any case; extra columns with commas, quotes and line breaks
python3 - "$D" <<'PY'
import random, sys
d = sys.argv[1]
rnd = random.Random(32)
floors = [('bldA', '01-ground', 'Ground level (RG 1.60, 0.3 g)'), ('bldA', '02-el12', 'Floor el. 12 m'),
          ('bld-B', '03-el24', 'Floor el. 24 m'), ('bld-B', '04-roof36', 'Roof el. 36 m')]
def rows(prefix, n):
    out = []
    for i in range(n):
        b, fid, name = floors[i % 4]
        fl = [fid, name, name.upper(), fid.upper()][rnd.randrange(4)]
        mu = rnd.choice([0.05, 0.1, 0.2, 0.3, 0.5, round(rnd.uniform(0.03, 0.56), 3), round(rnd.uniform(0.05, 0.5), 4)])
        cg = round(rnd.uniform(0.3, 1.5), 2)
        base = round(rnd.uniform(0.25, 3.0), 2)
        gap = round(rnd.choice([0, rnd.uniform(0, 60), rnd.uniform(0, 900), rnd.uniform(100, 900)]), 1)
        out.append(['%s-%02d' % (prefix, i + 1), b if rnd.random() < 0.8 else b.upper(), fl, repr(mu), repr(base), repr(cg), repr(gap),
                    rnd.choice(['tool cart', 'cabinet, 2 doors', 'tank "T-1"', 'ladder\nrack', '']), 'R%d' % rnd.randrange(100)])
    return out
def field(s):
    return '"' + s.replace('"', '""') + '"' if any(c in s for c in ',"\r\n') else s
A = rows('A', 40)
A[0][1:7] = ['bld-B', '04-roof36', '0.2', '2', '1', 'EXACT']   # the gap exactly the table's value at a grid point
A[1][3:6] = ['0.04', '3', '0.5']    # below the grid, squat
A[2][3:6] = ['0.55', '3', '0.5']    # above the grid, squat
A[3][3:6] = ['0.3', '0.5', '1.2']   # slender: b/h 0.21
A[4][1:7] = ['bldA', '02-el12', '0.3', '2', '1', 'MARGIN']   # the gap one SE above the table's value
A[5][1:7] = ['bldA', '01-ground', '0.7', '1.4', '1', '5']   # squat but mu >= b/h 0.7: rocks, stands
A[6][1:7] = ['bldA', '02-el12', '0.5', '1', '1', '10']      # rocks without tipping, its top 10 mm off: short
Bx = rows('B', 10)
Bx[0][1:7] = ['bld-B', '04-roof36', '0.2', '2', '1', 'EXACT']   # typed in: the same tie
Bx[1][1:7] = ['bldA', 'Ground level (RG 1.60, 0.3 g)', '0.3', '0.5', '1.2', '40']   # by name; slender
Bx[2][1:7] = ['BLDA', '  FLOOR   el. 12 M ', '0.3', '2', '1', 'MARGIN']   # marginal; names as TRIM and MATCH read them
head = ['Tag', 'BUILDING', 'floor', 'Mu', 'base_m', 'cg_height_m', 'clearance_mm', 'description', 'room']
with open(d + '/a.csv', 'w', newline='') as f:
    f.write('\ufeff# components of the test plant\r\n' + ','.join(head) + '\r\n')
    for r in A:
        f.write(','.join(field(x) for x in r) + '\r\n')
with open(d + '/ab.csv', 'w', newline='') as f:
    f.write(','.join(head) + '\n')
    for r in A + Bx:
        f.write(','.join(field(x) for x in r) + '\n')
with open(d + '/b.tsv', 'w') as f:   # the rows to type in: tab-separated, newlines as \n
    for r in Bx:
        f.write('\t'.join(x.replace('\n', '\\n') for x in r) + '\n')
PY
# the exact tie: the roof's clearance at mu 0.2 as its table gives it
tie=$(awk -F, '/^0.2,/ {print $12}' "$D/res/bld-B/floor_04-roof36.csv")
sed -i "s/,EXACT,/,$tie,/" "$D/a.csv" "$D/ab.csv"
sed -i "s/\tEXACT\t/\t$tie\t/" "$D/b.tsv"
# one standard error of margin: the gap the table's clearance plus its SE at mu 0.3
mg=$(awk -F, '/^0.3,/ {printf "%.4f", $12 + $6}' "$D/res/bldA/floor_02-el12.csv")
sed -i "s/,MARGIN,/,$mg,/" "$D/a.csv" "$D/ab.csv"
sed -i "s/\tMARGIN\t/\t$mg\t/" "$D/b.tsv"

t_run components "$D/res" "$D/a.csv" -o "$D/cout" --created 1700000000
t_expect_rc components 0
tail -1 "$T_ERR" | grep -Eq '^seislide: 40 components: [0-9]+ ok, [0-9]+ stands, [0-9]+ marginal, [0-9]+ short, [0-9]+ overturns, [0-9]+ outside$' && t_pass ||
  t_fail "last stderr line: $(tail -1 "$T_ERR")"
for f in components.csv components.xlsx; do [ -s "$D/cout/$f" ] && t_pass || t_fail "missing $f"; done

# the independent recomputation: every row from the floor tables
cat > "$D/recompute.py" <<'PY'
import csv, io, sys, os
res, comp, out = sys.argv[1], sys.argv[2], sys.argv[3]
def table(path):
    lines = [l for l in open(path, newline='', encoding='utf-8-sig').read().splitlines(True) if not l.startswith('#')]
    return list(csv.DictReader(io.StringIO(''.join(lines))))
plant = os.path.exists(res + '/plant.csv')
blds = sorted(x for x in os.listdir(res) if os.path.exists('%s/%s/floors.csv' % (res, x))) if plant else ['']
fl = {}
for b in blds:
    for r in table('%s/%s/floors.csv' % (res, b)):
        t = table('%s/%s/floor_%s.csv' % (res, b, r['floor_id']))
        g = ([float(x['mu']) for x in t], [float(x['clearance_mm']) for x in t], [float(x['nltha_design_se_mm']) for x in t],
             [float(x['asce_design_mm']) for x in t])
        fl[(b.lower(), r['floor_id'].lower())] = g
        fl[(b.lower(), r['floor'].lower())] = g
def interp(mu, xs, ys):
    if mu < xs[0] or mu > xs[-1]:
        return None
    for i in range(len(xs) - 1):
        if xs[i] <= mu <= xs[i + 1]:
            if mu == xs[i + 1]:
                return ys[i + 1]
            t = (mu - xs[i]) / (xs[i + 1] - xs[i])
            return ys[i] * (1 - t) + ys[i + 1] * t
    return ys[-1]
got = table(out)
want = [w for w in table(comp) if any((v or '').strip() for v in w.values())]   # rows of empty fields skipped
n = bad = 0
counts = {}
for w, g in zip(want, got):
    k = {c.lower(): v for c, v in w.items()}
    b = k['building'].strip().lower() if plant else ''
    xs, cs, ss, asce = fl[(b, k['floor'].strip().lower())]
    mu, base, h, gap = (float(k[c]) for c in ('mu', 'base_m', 'cg_height_m', 'clearance_mm'))
    req = interp(mu, xs, cs)
    se = interp(mu, xs, ss)
    a = interp(mu, xs, asce)
    # Shenton (1996): sliding before rocking only when mu < b/h, b half the base, h the CG height;
    # a margin inside two standard errors of the required clearance is marginal; a rocking
    # row's verdict by the rule of its own columns (ASCE/SEI 43-05 targets 1 % and 10 %)
    if mu >= (base / 2) / h:
        p1, s1, p2, s2, e = (float(g[c]) for c in ('p_tip', 'p_tip_se', 'p_tip_15', 'p_tip_15_se', 'excursion_mm'))
        near = (s1 > 0 and 0.01 - p1 <= 2 * s1) or (s2 > 0 and 0.10 - p2 <= 2 * s2)
        v = ('overturns' if p1 > 0.01 or p2 > 0.10 else 'short' if e > gap else 'marginal' if near
             else 'stands')
        if g['mode'] != 'rocking' or g['rocking_verdict'] != v:
            print('FAIL %s: mode %s rocking_verdict %s, recomputed %s' % (k['tag'], g['mode'], g['rocking_verdict'], v))
    else:
        v = ('outside' if req is None else 'short' if gap - req < 0
             else 'marginal' if gap - req < 2 * se else 'ok')
    counts[v] = counts.get(v, 0) + 1
    n += 1
    msg = []
    if g['verdict'] != v:
        msg.append('verdict %s, recomputed %s' % (g['verdict'], v))
    if req is not None:
        for name, val in (('required_clearance_mm', req), ('required_clearance_se_mm', se), ('margin_mm', gap - req),
                          ('asce_design_mm', a)):
            if abs(float(g[name]) - val) > 0.051:
                msg.append('%s %s, recomputed %.4f' % (name, g[name], val))
    elif g['required_clearance_mm'] or g['margin_mm']:
        msg.append('a required clearance off the grid')
    if any(g[c] != w[c] for c in w):
        msg.append('input columns changed')
    if msg:
        bad += 1
        print('FAIL %s: %s' % (k['tag'], '; '.join(msg)))
print('rows %d bad %d %s' % (n, bad, ' '.join('%s=%d' % x for x in sorted(counts.items()))))
PY
python3 "$D/recompute.py" "$D/res" "$D/a.csv" "$D/cout/components.csv" > "$D/re.txt" 2>&1
grep FAIL "$D/re.txt" | head -5 >&2
grep -Eq '^rows 40 bad 0 marginal=[1-9][0-9]* ok=[1-9][0-9]* outside=[1-9][0-9]* overturns=[1-9][0-9]* short=[1-9][0-9]*( stands=[0-9]+)?$' "$D/re.txt" && ! grep -q FAIL "$D/re.txt" && t_pass ||
  t_fail "recomputed components: $(tail -1 "$D/re.txt") (every verdict must occur)"
# the counts line agrees with the file
c=$(python3 -c "
import csv,sys,io
r=list(csv.DictReader(io.StringIO(''.join(l for l in open(sys.argv[1],newline='') if not l.startswith('#')))))
print('40 components: %d ok, %d stands, %d marginal, %d short, %d overturns, %d outside' % tuple(sum(x['verdict']==v for x in r) for v in ('ok','stands','marginal','short','overturns','outside')))" "$D/cout/components.csv")
tail -1 "$T_ERR" | grep -qF "$c" && t_pass || t_fail "counts '$(tail -1 "$T_ERR")', the file gives '$c'"
# the exact tie: margin 0, inside two standard errors: marginal; the trace lines of every CSV
tie=$(python3 -c "
import csv,sys,io
r=[x for x in csv.DictReader(io.StringIO(''.join(l for l in open(sys.argv[1],newline='') if not l.startswith('#')))) if x['Tag']=='A-01']
print(r[0]['margin_mm'], r[0]['verdict'])" "$D/cout/components.csv")
[ "$tie" = "0.0 marginal" ] && t_pass || t_fail "the exact tie: margin and verdict '$tie', expected '0.0 marginal'"
for l in '# program: seislide' '# command: seislide components ' '# created: 2023-11-14T22:13:20Z' '# seed: 1' \
         '# floor_file_crc32: [0-9a-f]{8} bldA/01-ground ' '# components_file: .*a.csv \([0-9a-f]{8}, [0-9]+ bytes\)' '# results: '; do
  grep -Eq "^$l" "$D/cout/components.csv" && t_pass || t_fail "components.csv has no line /$l/"
done
# one building: building empty or the folder's name
printf 'tag,building,floor,mu,base_m,cg_height_m,clearance_mm\nX1,,01-ground,0.25,2,1,100\n,,,,,,\nX2,res1,Roof el. 36 m,0.1,2,1,50\n' > "$D/one.csv"
t_run components "$D/res1" "$D/one.csv" -o "$D/out1" --created 1700000000; t_expect_rc one-building 0
python3 "$D/recompute.py" "$D/res1" "$D/one.csv" "$D/out1/components.csv" > "$D/re1.txt" 2>&1
grep -q '^rows 2 bad 0' "$D/re1.txt" && t_pass || t_fail "one building: $(cat "$D/re1.txt")"

# run --components: the same file beside plant.csv, the same rows as the command's
t_run run "$D/plant" -o "$D/res2" $OPTS --components "$D/a.csv"; t_expect_rc run-components 0
t_expect_err run-components-counts '^seislide: 40 components: '
grep -v '^#' "$D/res2/components.csv" > "$D/c2"; grep -v '^#' "$D/cout/components.csv" > "$D/c1"
cmp -s "$D/c1" "$D/c2" && t_pass || t_fail "run --components gives other rows than seislide components"
[ -s "$D/res2/plant.csv" ] && [ -s "$D/res2/components.xlsx" ] && t_pass || t_fail "run --components: outputs missing"
grep -q "^# results: $D/res2 (a plant; " "$D/res2/components.csv" && t_pass ||
  t_fail "run --components names its results: $(grep '^# results' "$D/res2/components.csv")"
# one building: a row may name the output folder as its building
printf 'tag,building,floor,mu,base_m,cg_height_m,clearance_mm\nY1,res4,04-roof36,0.3,2,1,500\n' > "$D/one4.csv"
t_run run "$D/one" -o "$D/res4" $OPTS --components "$D/one4.csv"; t_expect_rc run-components-one 0
t_expect_err run-components-one 'seislide: 1 components: 1 ok, 0 stands, 0 marginal, 0 short, 0 overturns, 0 outside'
# a later run into the same folder accepts the components outputs as its own
t_run run "$D/plant" -o "$D/res2" $OPTS; t_expect_rc rerun-over-components 0

# malformed rows: exit 1, file:line(:col) and the value named, nothing written
H='tag,building,floor,mu,base_m,cg_height_m,clearance_mm'
n=0
bad_case() { # NAME, REGEX of the message, then the file's lines
  name=$1; re=$2; shift 2; n=$((n + 1))
  printf '%s\n' "$@" > "$D/bad$n.csv"
  t_run components "$D/res" "$D/bad$n.csv" -o "$D/badout"
  t_expect_rc "$name" 1
  t_expect_err "$name" "bad$n.csv:$re"
  [ -e "$D/badout" ] && t_fail "$name: an output folder was written" || t_pass
}
bad_case non-numeric-mu '3:4: non-numeric value .abc.' "$H" 'a,bldA,01-ground,0.2,1,1,10' 'b,bldA,01-ground,abc,1,1,10'
bad_case mu-zero '2:4: value 0 must be > 0' "$H" 'a,bldA,01-ground,0,1,1,10'
bad_case base-negative '2:5: value -1 must be > 0' "$H" 'a,bldA,01-ground,0.2,-1,1,10'
bad_case height-zero '2:6: value 0 must be > 0' "$H" 'a,bldA,01-ground,0.2,1,0,10'
bad_case clearance-negative '2:7: value -5 must be >= 0' "$H" 'a,bldA,01-ground,0.2,1,1,-5'
bad_case clearance-text '2:7: non-numeric value .10 mm.' "$H" 'a,bldA,01-ground,0.2,1,1,10 mm'
bad_case unknown-building "3:2: unknown building 'bldC'; the buildings: bld-B, bldA" "$H" 'a,bldA,01-ground,0.2,1,1,10' 'b,bldC,01-ground,0.2,1,1,10'
bad_case empty-building-plant "2:2: no building; the buildings: bld-B, bldA" "$H" 'a,,01-ground,0.2,1,1,10'
bad_case unknown-floor "2:3: unknown floor 'roof' in building bld-B; its floors \(id \(name\)\): 03-el24 \(Floor el. 24 m\), 04-roof36 \(Roof el. 36 m\)" "$H" 'a,bld-B,roof,0.2,1,1,10'
bad_case floor-of-other-building "2:3: unknown floor '01-ground' in building bld-B" "$H" 'a,bld-B,01-ground,0.2,1,1,10'
bad_case duplicate-tag "4:1: tag 'a' again: first on line 2" "$H" 'A,bldA,01-ground,0.2,1,1,10' 'b,bldA,01-ground,0.2,1,1,10' 'a,bldA,01-ground,0.3,1,1,10'
bad_case empty-tag '2:1: empty tag' "$H" ',bldA,01-ground,0.2,1,1,10'
bad_case missing-field '2:7: 6 fields; the header has 7' "$H" 'a,bldA,01-ground,0.2,1,1'
bad_case missing-column "1: no column 'clearance_mm'" 'tag,building,floor,mu,base_m,cg_height_m' 'a,bldA,01-ground,0.2,1,1'
bad_case open-quote '2:8: a quoted field is not closed' "$H,note" 'a,bldA,01-ground,0.2,1,1,10,"open'
bad_case nan '2:4: (non-finite|non-numeric) value .nan.' "$H" 'a,bldA,01-ground,nan,1,1,10'
# a row after a quoted field with a line break is named by its own line
bad_case line-after-break '4:4: non-numeric' "$H,note" 'a,bldA,01-ground,0.2,1,1,10,"two' 'lines"' 'b,bldA,01-ground,x,1,1,10,'
# every bad row of a list in one pass, each with file:line:column, then how
# many; nothing written
printf '%s\n' "$H" 'a,bldA,01-ground,0.2,1,1,10' 'b,bldA,attic,x,1,1,10' 'c,bldA,01-ground,0.2,1' \
  'd,bldA,01-ground,0.2,1,1,10' 'A,bldA,01-ground,0.2,1,0,-3' > "$D/many.csv"
t_run components "$D/res" "$D/many.csv" -o "$D/badout"; t_expect_rc many-bad-rows 1
grep -c '^seislide: ' "$T_ERR" | grep -qx 7 && t_pass || t_fail "many bad rows: $(grep -c '^seislide: ' "$T_ERR") messages, expected 6 and the count"
for re in 'many.csv:3:3: unknown floor .attic.' 'many.csv:3:4: non-numeric value .x.' 'many.csv:4:6: 5 fields; the header has 7' \
          "many.csv:6:1: tag 'A' again: first on line 2" 'many.csv:6:6: value 0 must be > 0' 'many.csv:6:7: value -3 must be >= 0' \
          'many.csv: 3 of 5 rows refused \(6 problems\); nothing written$'; do
  t_expect_err many-bad-rows "$re"
done
[ -e "$D/badout" ] && t_fail "many bad rows: an output folder was written" || t_pass
# a list saved by a European spreadsheet: ';' between fields, decimal commas;
# the same rows as the list with ',' and points
python3 - "$D/a.csv" "$D/a-semi.csv" <<'PY'
import csv, sys
rows = list(csv.reader(l for l in open(sys.argv[1], newline='', encoding='utf-8-sig') if not l.startswith('#')))
with open(sys.argv[2], 'w', newline='', encoding='utf-8') as f:
    w = csv.writer(f, delimiter=';', lineterminator='\r\n')
    w.writerow(rows[0])
    w.writerows([x.replace('.', ',') if i in (3, 4, 5, 6) else x for i, x in enumerate(r)] for r in rows[1:])
PY
t_run components "$D/res" "$D/a-semi.csv" -o "$D/csemi" --created 1700000000; t_expect_rc semicolon-list 0
python3 - "$D/cout/components.csv" "$D/csemi/components.csv" > "$D/semi.txt" <<'PY'
import csv, io, sys
def rows(p):
    return list(csv.reader(io.StringIO(''.join(l for l in open(p, newline='', encoding='utf-8') if not l.startswith('#')))))
a, b = rows(sys.argv[1]), rows(sys.argv[2])
print('same' if len(a) == 41 and [r[-7:] for r in a] == [r[-7:] for r in b] else 'differ')
PY
grep -qx same "$D/semi.txt" && t_pass || t_fail "a ';' list with decimal commas gives other results than the ',' list"
printf 'tag;building;floor;mu;base_m;cg_height_m;clearance_mm\nx;bldA;01-ground;0,2;1;1;1.234,5\n' > "$D/semi-bad.csv"
t_run components "$D/res" "$D/semi-bad.csv" -o "$D/badout"; t_expect_rc semicolon-thousands 1
t_expect_err semicolon-thousands "semi-bad.csv:2:7: '1.234,5' mixes ',' and '.'"
# one building: a building other than the folder's
printf '%s\n' "$H" 'a,other,01-ground,0.2,1,1,10' > "$D/bad1b.csv"
t_run components "$D/res1" "$D/bad1b.csv" -o "$D/badout"; t_expect_rc one-building-unknown 1
t_expect_err one-building-unknown "bad1b.csv:2:2: unknown building 'other': the results are one building \(folder 'res1'\)"
# not results; usage
t_run components "$D/plant" "$D/a.csv" -o "$D/badout"; t_expect_rc not-results 1
t_expect_err not-results "not the output folder of seislide run"
t_run components "$D/res" "$D/a.csv"; t_expect_rc no-output 2
t_run components --help; t_expect_rc help 0; t_expect_out help '^usage: seislide components RESULTS COMPONENTS.csv -o OUT'
# run --components with a malformed list: the run fails, its folder unchanged
t_run run "$D/plant" -o "$D/res3" $OPTS --components "$D/bad1.csv"; t_expect_rc run-bad-components 1
[ -e "$D/res3/plant.csv" ] && t_fail "run --components with a bad list wrote its outputs" || t_pass

# the workbook: rows typed below the last component, recalculated by
# LibreOffice, equal what components.csv gives for them
if command -v soffice >/dev/null 2>&1; then
  python3 - "$D/cout/components.xlsx" "$D/typed.xlsx" "$D/b.tsv" 40 <<'PY'
import sys, zipfile, re
src, dst, rows, n0 = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
z = zipfile.ZipFile(src)
wb = z.read('xl/workbook.xml').decode()
first = re.search(r'<sheet name="([^"]+)"', wb).group(1)
assert first == 'Components', first
x = z.read('xl/worksheets/sheet1.xml').decode()
def esc(s):
    return s.replace('&', '&amp;').replace('<', '&lt;').replace('>', '&gt;')
for i, line in enumerate(open(rows).read().splitlines()):
    f = line.split('\t')
    r = 4 + n0 + i   # header on row 3, the components from row 4
    vals = f[:7] + f[7:9]
    for c, v in enumerate(vals):
        ref = '%s%d' % ('ABCDEFGHI'[c], r)
        m = re.search(r'<c r="%s"( s="\d+")?/>' % ref, x)
        assert m, ref
        v = v.replace('\\n', '\n')
        if 3 <= c <= 6:
            cell = '<c r="%s"%s><v>%s</v></c>' % (ref, m.group(1) or '', v)
        else:
            cell = '<c r="%s"%s t="inlineStr"><is><t xml:space="preserve">%s</t></is></c>' % (ref, m.group(1) or '', esc(v))
        x = x[:m.start()] + cell + x[m.end():]
out = zipfile.ZipFile(dst, 'w', zipfile.ZIP_DEFLATED)
for it in z.infolist():
    out.writestr(it, x if it.filename == 'xl/worksheets/sheet1.xml' else z.read(it.filename))
out.close()
PY
  t_run components "$D/res" "$D/ab.csv" -o "$D/outab" --created 1700000000; t_expect_rc components-ab 0
  # a private profile that recalculates every formula on load (as tests/test_lookup.c)
  mkdir -p "$D/lo/user"
  cat > "$D/lo/user/registrymodifications.xcu" <<'XCU'
<?xml version="1.0" encoding="UTF-8"?>
<oor:items xmlns:oor="http://openoffice.org/2001/registry" xmlns:xs="http://www.w3.org/2001/XMLSchema" xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance">
<item oor:path="/org.openoffice.Office.Calc/Formula/Load"><prop oor:name="OOXMLRecalcMode" oor:op="fuse"><value>0</value></prop></item>
</oor:items>
XCU
  (cd "$D" && timeout 180 soffice -env:UserInstallation=file://$D/lo --headless --convert-to \
    'csv:Text - txt - csv (StarCalc):44,34,76,1,,0,false,true,false,false' --outdir lo_csv typed.xlsx >/dev/null 2>&1)
  python3 - "$D/lo_csv/typed.csv" "$D/outab/components.csv" > "$D/lo.txt" 2>&1 <<'PY'
import csv, io, sys
sheet = list(csv.reader(open(sys.argv[1], newline='', encoding='utf-8')))
want = list(csv.DictReader(io.StringIO(''.join(l for l in open(sys.argv[2], newline='') if not l.startswith('#')))))
head = sheet[2]
col = {h: i for i, h in enumerate(head)}
bad = 0
checked = 0
for w in want:
    rows = [r for r in sheet[3:] if r and r[0] == w['Tag']]
    if len(rows) != 1:
        print('FAIL %s: %d rows on the sheet' % (w['Tag'], len(rows))); bad += 1; continue
    r = rows[0]
    msg = []
    # a slender row typed into the sheet is not computed there: "rocking", and the
    # command computes it; a row the command wrote keeps its computed verdict and
    # reason, the excursion set against its clearance by formula
    typed_rock = w['Tag'].startswith('B-') and w['mode'] == 'rocking'
    wv = 'rocking' if typed_rock else w['verdict']
    wr = w['reason']
    if typed_rock:
        def fm(x):   # TEXT(x, "0.0##")
            t = ('%.3f' % float(x)).rstrip('0')
            return t + '0' if t.endswith('.') else t
        lw = {c.lower(): v for c, v in w.items()}
        wr = 'mu %s >= b/h %s: rocks before it slides; its rocking is computed by seislide components' % (
            fm(lw['mu']), fm(lw['b_over_h']))
    if r[col['verdict']] != wv:
        msg.append('verdict %s, csv %s' % (r[col['verdict']], wv))
    if r[col['reason']] != wr:
        msg.append('reason %r, csv %r' % (r[col['reason']], wr))
    for sc, cc in (('required, mm', 'required_clearance_mm'), ('its SE, mm', 'required_clearance_se_mm'), ('margin, mm', 'margin_mm'),
                   ('ASCE, mm', 'asce_design_mm')):
        a, b = r[col[sc]], w[cc]
        if (a == '') != (b == '') or (a and abs(float(a) - float(b)) > 0.05 + 1e-9):
            msg.append('%s %s, csv %s' % (sc, a, b))
    checked += w['Tag'].startswith('B-')
    if msg:
        bad += 1
        print('FAIL %s: %s' % (w['Tag'], '; '.join(msg)))
print('rows %d typed %d bad %d' % (len(want), checked, bad))
PY
  grep FAIL "$D/lo.txt" | head -5 >&2
  grep -q '^rows 50 typed 10 bad 0$' "$D/lo.txt" && t_pass || t_fail "LibreOffice recalculation: $(tail -1 "$D/lo.txt")"
  # printed (the workbook with the rows typed in, recalculated): every
  # Components page repeats the header row, the typed rows print with their
  # verdicts, the chart page is there
  if command -v pdftotext >/dev/null 2>&1; then
    (cd "$D" && timeout 180 soffice -env:UserInstallation=file://$D/lo --headless --convert-to pdf \
      --outdir pdf typed.xlsx >/dev/null 2>&1)
    pdftotext -layout "$D/pdf/typed.pdf" "$D/pdf.txt" 2>/dev/null
    python3 - "$D/pdf.txt" > "$D/pdfcheck.txt" <<'PY'
import sys
pages = open(sys.argv[1]).read().split('\f')[:-1]
comp = [p for p in pages if 'Components' in p.split('\n', 3)[0] + p.split('\n', 3)[1]]
ok = len(pages) >= 3 and all('clearance_mm' in p and 'verdict' in p for p in pages[:len(pages) - 2])
ok = ok and sum(p.count('A-') for p in pages) >= 40 and 'Available against required' in pages[-1]
typed = [t for t in ('B-%02d' % i for i in range(1, 11)) if not any(t in p for p in pages[:-2])]
ok = ok and not typed and any('marginal' in p for p in pages[:-2])
ok = ok and 'Components: counts per verdict' in pages[-2]
print('ok' if ok else 'FAIL pages %d, typed rows not printed: %s' % (len(pages), typed))
PY
    grep -q '^ok' "$D/pdfcheck.txt" && t_pass || t_fail "printed components.xlsx: $(cat "$D/pdfcheck.txt")"
  else
    t_skip "pdftotext absent: components.xlsx as printed not checked"
  fi
else
  t_skip "soffice (LibreOffice) not found: the Components sheet is not recalculated; install libreoffice-calc-nogui"
fi
# names as written (UTF-8): a plant whose building and floor carry non-ASCII
# names (tests/cli/test_plant.sh's construction; here the floor's name differs
# from its id), while its output folder and floor CSV are named by
# sl_report_file_name ("Bâtiment_réacteur/floor_Niveau_−3_m.csv")
U="$D/plantu"; RB='Bâtiment réacteur'; NV='Niveau −3 m'; NN='Salle des pompes −3 m'
mkdir -p "$U/$RB" "$U/Aux"
sed -e "s/^name = .*/name = $NN/" floors/01-ground.ini > "$U/$RB/$NV.ini"
cp floors/02-el12.ini "$U/Aux/"
t_run run "$U" -o "$D/resu" $OPTS; t_expect_rc utf8-run 0
printf 'tag,building,floor,mu,base_m,cg_height_m,clearance_mm,room\n' > "$D/u.csv"
# U-4: the building and the floor in other cases, as the sheet's MATCH finds them
printf 'U-1,%s,%s,0.3,3,0.5,900,salle −3\nU-2,%s,%s,0.2,3,0.5,1,\nU-3,Aux,02-el12,0.3,3,0.5,900,\nU-4,bâtiment RÉACTEUR,NIVEAU −3 M,0.3,3,0.5,900,\n' \
  "$RB" "$NV" "$RB" "$NN" >> "$D/u.csv"
t_run components "$D/resu" "$D/u.csv" -o "$D/coutu" --created 1700000000; t_expect_rc utf8-components 0
t_expect_err utf8-summary '4 components: 3 ok, 0 stands, 0 marginal, 1 short, 0 overturns, 0 outside'
# each row's required clearance is its floor table's at its mu, the building and
# floor written back as given, the extra column kept
python3 - "$D" "$RB" "$NV" "$NN" > "$D/u.txt" 2>&1 <<'PY'
import csv, sys
d, rb, nv, nn = sys.argv[1:5]
def table(path):
    rows = [l for l in open(path, encoding='utf-8') if not l.startswith('#')]
    return {float(r['mu']): float(r['clearance_mm']) for r in csv.DictReader(rows)}
t = table(d + '/resu/Bâtiment_réacteur/floor_Niveau_−3_m.csv')
a = table(d + '/resu/Aux/floor_02-el12.csv')
rows = [l for l in open(d + '/coutu/components.csv', encoding='utf-8') if not l.startswith('#')]
out = {r['tag']: r for r in csv.DictReader(rows)}
def ok(c, what):
    print(('ok ' if c else 'FAIL ') + what)
for tag, ref, b, f in (('U-1', t[0.3], rb, nv), ('U-2', t[0.2], rb, nn), ('U-3', a[0.3], 'Aux', '02-el12')):
    r = out.get(tag, {})
    ok(abs(float(r.get('required_clearance_mm', 'nan')) - ref) <= 0.006 * ref + 0.05,  # as printed
       '%s: required %s against the floor table %g' % (tag, r.get('required_clearance_mm'), ref))
    ok(r.get('building') == b and r.get('floor') == f, '%s: building and floor as given: %s, %s' % (tag, r.get('building'), r.get('floor')))
ok(out.get('U-1', {}).get('room') == 'salle −3', 'extra column kept as written')
ok(out.get('U-2', {}).get('verdict') == 'short', 'U-2 short (1 mm gap)')
PY
! grep -q '^FAIL' "$D/u.txt" && [ "$(grep -c '^ok ' "$D/u.txt")" -eq 8 ] && t_pass || t_fail "non-ASCII names: $(grep -v '^ok ' "$D/u.txt" | head -3)"
# unknown names: the known ones listed as written, the name given shown as written
printf 'tag,building,floor,mu,base_m,cg_height_m,clearance_mm\nV-1,Batiment reacteur,%s,0.3,3,0.5,9\n' "$NV" > "$D/bu1.csv"
t_run components "$D/resu" "$D/bu1.csv" -o "$D/badu"; t_expect_rc utf8-unknown-building 1
t_expect_err utf8-unknown-building "bu1.csv:2:2: unknown building 'Batiment reacteur'; the buildings: Aux, $RB"
printf 'tag,building,floor,mu,base_m,cg_height_m,clearance_mm\nV-1,%s,Niveau −4 m,0.3,3,0.5,9\n' "$RB" > "$D/bu2.csv"
t_run components "$D/resu" "$D/bu2.csv" -o "$D/badu"; t_expect_rc utf8-unknown-floor 1
t_expect_err utf8-unknown-floor "bu2.csv:2:3: unknown floor 'Niveau −4 m' in building $RB; its floors \\(id \\(name\\)\\): $NV \\($NN\\)"
[ -e "$D/badu" ] && t_fail "a refused list wrote $D/badu" || t_pass
# run --components on that plant, then a rerun into the same folder: the
# manifest names components.csv and .xlsx, the rerun replaces them, a user's
# file in the folder survives
t_run run "$U" -o "$D/runu" $OPTS --components "$D/u.csv"; t_expect_rc utf8-run-components 0
grep -qx 'components.csv' "$D/runu/.seislide-manifest" && grep -qx 'components.xlsx' "$D/runu/.seislide-manifest" &&
  t_pass || t_fail "manifest lacks the components outputs: $(cat "$D/runu/.seislide-manifest" | tr '\n' ' ')"
grep -v '^#' "$D/runu/components.csv" > "$D/cu1"; grep -v '^#' "$D/coutu/components.csv" > "$D/cu2"
cmp -s "$D/cu1" "$D/cu2" && t_pass || t_fail "run --components gives other rows than seislide components"
echo 'my notes' > "$D/runu/notes.txt"
sed -e 's/,900,/,0,/' "$D/u.csv" > "$D/u2.csv"
t_run run "$U" -o "$D/runu" $OPTS --components "$D/u2.csv"; t_expect_rc utf8-rerun-components 0
[ "$(cat "$D/runu/notes.txt" 2>/dev/null)" = 'my notes' ] && t_pass || t_fail "the rerun lost the user's notes.txt"
grep -q '^U-1,.*,short,' "$D/runu/components.csv" && t_pass || t_fail "the rerun did not replace components.csv: $(grep '^U-1' "$D/runu/components.csv")"
grep -qx 'notes.txt' "$D/runu/.seislide-manifest" && t_fail "the manifest claims the user's file" || t_pass

t_end
