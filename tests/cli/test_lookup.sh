#!/bin/sh
# End-to-end tests of `seislide lookup` (docs/run.md, "One floor at one
# mu"): on every floor of the example facility at 5 friction values (a grid
# row, between rows, the grid's two ends, a third point), the clearance, its
# SE and the ASCE value against this script's own interpolation of the
# floor CSVs, the flags of the two grid rows and the floor's ZPA, sets and
# note against the tables; floors by id and by name in other cases and with
# extra blanks; a plant's building in other cases; the Lookup sheet of the
# workbook, its inputs set to the same floor and mu and recalculated by
# LibreOffice, gives the same clearance; errors: an unknown building or
# floor lists the known ones, mu off the grid, usage.
. "$(dirname "$0")/lib.sh"
t_suite cli_lookup
D=$T_TMP
if ! command -v python3 >/dev/null 2>&1; then
  t_skip "python3 absent: lookup not checked"; t_end; exit $?
fi
t_run run floors -o "$D/fac" --sets 2 --created 1700000000 -q --no-cache; t_expect_rc facility 0

# the five friction values on every floor, by id (as written, in upper case)
# and by name (other case, extra blanks)
: > "$D/got.csv"
n=0
for id in 01-ground 02-el12 03-el24 04-roof36; do
  name=$(python3 -c "
import csv, io, sys
r = csv.DictReader(io.StringIO(''.join(l for l in open(sys.argv[1]) if not l.startswith('#'))))
print([x['floor'] for x in r if x['floor_id'] == sys.argv[2]][0])" "$D/fac/floors.csv" "$id")
  up=$(printf '%s' "$id" | tr 'a-z' 'A-Z'); nm=$(printf '  %s ' "$name" | tr 'a-z' 'A-Z' | sed 's/ /  /g')
  for mu in 0.05 0.123 0.3 0.457 0.8; do
    n=$((n + 1))
    case $((n % 3)) in 0) f=$id ;; 1) f=$up ;; *) f=$nm ;; esac
    t_run lookup "$D/fac" --floor "$f" --mu "$mu" --csv
    [ "$T_RC" -eq 0 ] && t_pass || t_fail "lookup --floor '$f' --mu $mu: exit $T_RC ($(head -c 200 "$T_ERR"))"
    [ -s "$D/got.csv" ] || head -1 "$T_OUT" > "$D/got.csv"
    sed 1d "$T_OUT" >> "$D/got.csv"
  done
done
python3 - "$D/fac" "$D/got.csv" > "$D/check.txt" 2>&1 <<'PY'
import csv, io, sys
d, got = sys.argv[1], sys.argv[2]
def rows(p):
    return list(csv.DictReader(io.StringIO(''.join(l for l in open(p, encoding='utf-8') if not l.startswith('#')))))
floors = {r['floor_id']: r for r in rows(d + '/floors.csv')}
bad = n = 0
for g in rows(got):
    fid = g['floor_id']
    t = rows('%s/floor_%s.csv' % (d, fid))
    zpa = [l.split(': ')[1] for l in open('%s/floor_%s.csv' % (d, fid)) if l.startswith('# horizontal_zpa_g: ')][0]
    xs = [float(r['mu']) for r in t]
    mu = float(g['mu'])
    # the last grid row at or below mu, and the next (the workbook's MATCH(mu, grid, 1))
    k0 = max(i for i, x in enumerate(xs) if x <= mu)
    k1 = min(k0 + 1, len(xs) - 1)
    def at(col):
        c0, c1 = float(t[k0][col]), float(t[k1][col])
        return c0 if xs[k1] == xs[k0] else c0 + (mu - xs[k0]) * (c1 - c0) / (xs[k1] - xs[k0])
    msg = []
    for col, want in (('required_clearance_mm', at('clearance_mm')), ('required_clearance_se_mm', at('nltha_design_se_mm')),
                      ('asce_design_mm', at('asce_design_mm'))):
        if abs(float(g[col]) - want) > 0.05 + 1e-9:
            msg.append('%s %s, the table %.4f' % (col, g[col], want))
    if g['flags_below'] != t[k0]['flags'] or g['flags_above'] != t[k1]['flags']:
        msg.append('flags %s | %s, the table %s | %s' % (g['flags_below'], g['flags_above'], t[k0]['flags'], t[k1]['flags']))
    f = floors[fid]
    if (g['floor'], g['n_sets'], g['sets_stop'], g['note']) != (f['floor'], f['n_sets'], f['sets_stop'], f['note']):
        msg.append('floor record %s' % [g['floor'], g['n_sets'], g['sets_stop'], g['note']])
    if abs(float(g['zpa_h_g']) - float(zpa)) > 1e-9 or abs(float(g['mu_g_over_zpa']) - mu / float(zpa)) > 6e-5:
        msg.append('ZPA %s, mu g/ZPA %s' % (g['zpa_h_g'], g['mu_g_over_zpa']))
    n += 1
    if msg:
        bad += 1
        print('FAIL %s mu %s: %s' % (fid, g['mu'], '; '.join(msg)))
print('checked %d bad %d' % (n, bad))
PY
grep FAIL "$D/check.txt" | head -5 >&2
grep -qx 'checked 20 bad 0' "$D/check.txt" && t_pass || t_fail "lookup against the floor tables: $(tail -1 "$D/check.txt")"

# the text: the clearance to the digit of its SE, as the tables show it
t_run lookup "$D/fac" --floor 'floor el. 12 m' --mu 0.3; t_expect_rc text 0
t_expect_out text '^floor +02-el12 \(Floor el\. 12 m\)$'
t_expect_out text '^mu +0\.3 \(a grid row\)$'
t_expect_out text '^required clearance +[0-9]+(\.[0-9])? mm \(SE [0-9]+\.[0-9] mm; clearance policy nltha\)$'
python3 - "$T_OUT" > "$D/digits.txt" <<'PY'
import re, sys
t = open(sys.argv[1]).read()
m = re.search(r'required clearance +([0-9.]+) mm \(SE ([0-9.]+) mm', t)
v, se = m.group(1), float(m.group(2))
print('ok' if ('.' in v) == (se < 0.95) else 'FAIL %s with SE %s' % (v, se))
PY
grep -qx ok "$D/digits.txt" && t_pass || t_fail "the clearance's digits against its SE: $(cat "$D/digits.txt")"

# the workbook's Lookup, recalculated by LibreOffice, gives the same clearance
# (a floor at mu between grid rows, one workbook per floor, one LibreOffice run)
if command -v soffice >/dev/null 2>&1; then
  python3 - "$D/fac/seislide-clearance.xlsx" "$D" <<'PY'
import csv, io, re, sys, zipfile
src, d = sys.argv[1], sys.argv[2]
floors = list(csv.DictReader(io.StringIO(''.join(l for l in open(d + '/fac/floors.csv') if not l.startswith('#')))))
z = zipfile.ZipFile(src)
wb = z.read('xl/workbook.xml').decode()
assert re.search(r'<sheet name="([^"]+)"', wb).group(1) == 'Lookup'
x0 = z.read('xl/worksheets/sheet1.xml').decode()
def esc(s):
    return s.replace('&', '&amp;').replace('<', '&lt;').replace('>', '&gt;')
for i, (f, mu) in enumerate(zip(floors, ('0.123', '0.457', '0.3', '0.05'))):
    x = x0
    for ref, val, num in (('B11', f['floor'], False), ('B12', mu, True)):
        m = re.search(r'<c r="%s"( s="\d+")?( t="\w+")?(/>|>.*?</c>)' % ref, x)
        cell = ('<c r="%s"%s><v>%s</v></c>' if num else '<c r="%s"%s t="inlineStr"><is><t>%s</t></is></c>') % (ref, m.group(1) or '', esc(val))
        x = x[:m.start()] + cell + x[m.end():]
    out = zipfile.ZipFile('%s/lk%d.xlsx' % (d, i), 'w', zipfile.ZIP_DEFLATED)
    for it in z.infolist():
        out.writestr(it.filename, x if it.filename == 'xl/worksheets/sheet1.xml' else z.read(it.filename))
    out.close()
    open('%s/lk%d.want' % (d, i), 'w').write('%s %s\n' % (f['floor_id'], mu))
PY
  mkdir -p "$D/lo/user"
  cat > "$D/lo/user/registrymodifications.xcu" <<'XCU'
<?xml version="1.0" encoding="UTF-8"?>
<oor:items xmlns:oor="http://openoffice.org/2001/registry" xmlns:xs="http://www.w3.org/2001/XMLSchema" xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance">
<item oor:path="/org.openoffice.Office.Calc/Formula/Load"><prop oor:name="OOXMLRecalcMode" oor:op="fuse"><value>0</value></prop></item>
</oor:items>
XCU
  (cd "$D" && timeout 180 soffice -env:UserInstallation=file://$D/lo --headless --convert-to \
    'csv:Text - txt - csv (StarCalc):44,34,76,1,,0,false,true,false,false' --outdir lo_csv \
    lk0.xlsx lk1.xlsx lk2.xlsx lk3.xlsx >/dev/null 2>&1)
  for i in 0 1 2 3; do
    set -- $(cat "$D/lk$i.want")
    t_run lookup "$D/fac" --floor "$1" --mu "$2" --csv
    want=$(python3 -c "import csv,sys; print(list(csv.DictReader(open(sys.argv[1])))[0]['required_clearance_mm'])" "$T_OUT")
    got=$(python3 -c "import csv,sys; r=list(csv.reader(open(sys.argv[1], encoding='utf-8'))); print(r[13][1])" "$D/lo_csv/lk$i.csv" 2>/dev/null)
    python3 -c "import sys; sys.exit(0 if abs(float(sys.argv[1]) - float(sys.argv[2])) <= 0.05 + 1e-9 else 1)" "$got" "$want" 2>/dev/null &&
      t_pass || t_fail "the Lookup sheet on $1 at mu $2 gives '$got', lookup $want"
  done
else
  t_skip "soffice (LibreOffice) not found: lookup not compared with the Lookup sheet"
fi

# a plant: the building by the name rule, the floor of that building
mkdir -p "$D/plant/Bâtiment réacteur" "$D/plant/Aux"
cp floors/01-ground.ini "$D/plant/Bâtiment réacteur/"; cp floors/02-el12.ini "$D/plant/Aux/"
t_run run "$D/plant" -o "$D/pout" --sets 2 --mu 0.1,0.2,0.3 --created 1700000000 -q --no-cache; t_expect_rc plant 0
t_run lookup "$D/pout" --building 'bâtiment RÉACTEUR' --floor 01-ground --mu 0.25 --csv; t_expect_rc plant-lookup 0
t_expect_out plant-lookup '^"Bâtiment réacteur",01-ground,"Ground level \(RG 1.60, 0.3 g\)",0.25,'
t_run lookup "$D/pout" --floor 01-ground --mu 0.25; t_expect_rc plant-no-building 1
t_expect_err plant-no-building "pout: no building; the buildings: Aux, Bâtiment réacteur"
t_run lookup "$D/pout" --building Aux --floor 01-ground --mu 0.25; t_expect_rc plant-other-floor 1
t_expect_err plant-other-floor "unknown floor '01-ground' in building Aux; its floors \(id \(name\)\): 02-el12 \(Floor el. 12 m\)"
# errors
t_run lookup "$D/fac" --floor attic --mu 0.3; t_expect_rc unknown-floor 1
t_expect_err unknown-floor "fac: unknown floor 'attic'; its floors \(id \(name\)\): 01-ground \(Ground level \(RG 1.60, 0.3 g\)\), 02-el12"
t_run lookup "$D/fac" --floor 01-ground --mu 0.9; t_expect_rc off-grid 1
t_expect_err off-grid 'mu 0.9 outside the computed grid 0.05-0.8'
t_run lookup "$D/fac" --floor 01-ground --mu 0.3 --building other; t_expect_rc one-building-other 1
t_run lookup "$D/fac" --mu 0.3; t_expect_rc no-floor 2
t_run lookup "$D/fac" --floor 01-ground; t_expect_rc no-mu 2
t_run lookup "$D/fac" --floor 01-ground --mu -1; t_expect_rc negative-mu 2
t_run lookup floors --floor 01-ground --mu 0.3; t_expect_rc not-results 1
t_expect_err not-results 'not the output folder of seislide run'
t_run lookup --help; t_expect_rc help 0
t_expect_out help '^usage: seislide lookup RESULTS \[--building B\] --floor F --mu X \[--csv\]'
t_end
