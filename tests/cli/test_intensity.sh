#!/bin/sh
# The floors of one building checked against each other (issue 39; src/plant/intensity.h,
# docs/formats-floor.md "Floors of one building"): a floor in m/s2 labelled g, or in g
# labelled m/s2, whose ZPA still lies inside the plausible 0.01-5 g, is refused before any
# work, naming its file, the floor, its ZPA, the other floors' ZPAs and the likely unit,
# whichever floor slipped (the ground floor included), in a building and in a plant;
# --accept-floor runs it, and the warning is then where a designer looks: floors.csv's
# and plant.csv's column warnings, the Lookup and Summary sheets, the Notes, the
# Inputs; shards carry it to merge. Every other warning (an unusual ZPA for its units)
# lands in the same places.
. "$(dirname "$0")/lib.sh"
t_suite cli_intensity
D=$T_TMP
FAST="--sets 2 --mu 0.2,0.4 --created 1700000000 -q"
# scale FILE K: the floor file with every spectral value and ZPA times K (units as written)
scale() {
  awk -v k="$2" '
/^\[/ { key = ""; print; next }
/^[a-z_0-9.]+ *=/ { split($0, kv, "="); key = kv[1]; gsub(/ /, "", key) }
{ if (key !~ /^(sa_|zpa)/) { print; next }
  line = $0; pre = ""
  if (match(line, /=/)) { pre = substr(line, 1, RSTART); line = substr(line, RSTART + 1) }
  n = split(line, a, ","); out = ""
  for (i = 1; i <= n; i++) { v = a[i]; gsub(/ /, "", v); if (v != "") out = out (i > 1 ? ", " : " ") sprintf("%.6g", v * k) }
  print pre out }' "$1"
}
building() { # DIR: floors/ copied
  rm -rf "$1"; mkdir -p "$1"; cp floors/*.ini "$1/"
}
nothing() { # NAME DIR
  [ ! -e "$2" ] && t_pass || t_fail "$1: output written: $(ls "$2")"
}

# the example building as shipped: no refusal, no warning
t_run run floors -o "$D/ok" $FAST; t_expect_rc example 0
[ "$(grep -v '^#' "$D/ok/floors.csv" | head -1 | tr -d '\r' | awk -F, '{print $NF}')" = warnings ] && t_pass || t_fail "floors.csv: no column warnings"
[ "$(grep -v '^#' "$D/ok/floors.csv" | tail -n +2 | tr -d '\r' | awk -F, '$NF != "" ' | wc -l)" -eq 0 ] && t_pass || t_fail "floors.csv: a warning on the example floors"

# the ground floor in m/s2 labelled g: 2.94 "g", inside 0.01-5 g
building "$D/b1"; scale floors/01-ground.ini 9.80665 > "$D/b1/01-ground.ini"
t_run run "$D/b1" -o "$D/o1" $FAST; t_expect_rc ground-ms2 1
t_expect_err ground-ms2-msg "b1/01-ground.ini: floor 01-ground \('Ground level \(RG 1.60, 0.3 g\)', el. 0 m\): horizontal ZPA 2.94 g is 5.77 x the median of the other floors of its building \(02-el12 0.39 g at 12 m, 03-el24 0.51 g at 24 m, 04-roof36 0.63 g at 36 m\)"
t_expect_err ground-ms2-unit "its values are likely in m/s2, not g \(its ZPA would then be 0.3 g\).*--accept-floor 01-ground"
nothing ground-ms2 "$D/o1"
# without elevations only the median rule can tell: it does
mkdir -p "$D/b0"; for f in floors/*.ini; do grep -v '^elevation_m' "$f" > "$D/b0/$(basename "$f")"; done
scale floors/01-ground.ini 9.80665 | grep -v '^elevation_m' > "$D/b0/01-ground.ini"
t_run run "$D/b0" -o "$D/o0" $FAST; t_expect_rc no-elevations 1
t_expect_err no-elevations-msg "b0/01-ground.ini: floor 01-ground \('Ground level \(RG 1.60, 0.3 g\)'\): horizontal ZPA 2.94 g is 5.77 x the median of the other floors of its building \(02-el12 0.39 g, 03-el24 0.51 g, 04-roof36 0.63 g\)\. On physical"
# a middle floor the same way
building "$D/b2"; scale floors/02-el12.ini 9.80665 > "$D/b2/02-el12.ini"
t_run run "$D/b2" -o "$D/o2" $FAST; t_expect_rc el12-ms2 1
t_expect_err el12-ms2-msg "b2/02-el12.ini: floor 02-el12 .*horizontal ZPA 3.82 g is 7.5 x the median.*03-el24, 12 m above it, has 0.133 x its ZPA.*likely in m/s2, not g"
# the roof in g labelled m/s2: 0.064 g
building "$D/b3"; sed 's/^units = g/units = m\/s2/' floors/04-roof36.ini > "$D/b3/04-roof36.ini"
t_run run "$D/b3" -o "$D/o3" $FAST; t_expect_rc roof-g 1
t_expect_err roof-g-msg "b3/04-roof36.ini: floor 04-roof36 .*horizontal ZPA 0.0642 g is 0.165 x the median.*likely in g, not m/s2 \(its ZPA would then be 0.63 g\)"
# two floors: either may have slipped, both named
mkdir -p "$D/b4"; cp floors/04-roof36.ini "$D/b4/"; scale floors/01-ground.ini 9.80665 > "$D/b4/01-ground.ini"
t_run run "$D/b4" -o "$D/o4" $FAST; t_expect_rc pair 1
t_expect_err pair-msg "floor 01-ground .* and floor 04-roof36 .*b4/04-roof36.ini\) are out of line with each other"

# in a plant: the building named
mkdir -p "$D/p1"; building "$D/p1/bldA"; building "$D/p1/bldB"
scale floors/01-ground.ini 9.80665 > "$D/p1/bldA/01-ground.ini"
t_run run "$D/p1" -o "$D/op1" $FAST; t_expect_rc plant 1
t_expect_err plant-msg "bldA/01-ground.ini: floor 01-ground .*the other floors of building bldA \(02-el12"
# --accept-floor: an id two buildings have is ambiguous; one that names no floor is a usage error
t_run run "$D/p1" -o "$D/op1" $FAST --accept-floor 01-ground; t_expect_rc accept-ambiguous 2
t_expect_err accept-ambiguous-msg "accept-floor 01-ground: 2 floors have that id: give BUILDING/ID"
t_run run "$D/p1" -o "$D/op1" $FAST --accept-floor bldA/nope; t_expect_rc accept-unknown 2
t_expect_err accept-unknown-msg "accept-floor bldA/nope: no such floor \(the floors: bldA/01-ground, "

# accepted in writing: it runs, and says so wherever a designer looks
t_run run "$D/b1" -o "$D/acc" $FAST --accept-floor 01-GROUND; t_expect_rc accepted 0
t_expect_err accepted-stderr "run: warning: .*b1/01-ground.ini: accepted by --accept-floor: horizontal ZPA 2.94 g"
w=$(grep '^01-ground,' "$D/acc/floors.csv")
case $w in *',"accepted by --accept-floor: horizontal ZPA 2.94 g'*"its values are likely in m/s2, not g"*) t_pass ;;
  *) t_fail "floors.csv: the accepted floor's warning: '$w'" ;; esac
# an accepted floor is no reference for the others: beside it, 02-el12 (0.133 x its ZPA)
# stands alone, nothing to compare with
mkdir -p "$D/b6"; cp floors/02-el12.ini "$D/b6/"; scale floors/01-ground.ini 9.80665 > "$D/b6/01-ground.ini"
t_run run "$D/b6" -o "$D/acc6" $FAST --accept-floor 01-ground; t_expect_rc accepted-alone 0
# an unusual ZPA for its units (one floor, nothing to compare with): the same column
sed 's/^units = g/units = m\/s2/' floors/01-ground.ini > "$D/low.ini"
t_run run "$D/low.ini" -o "$D/low" $FAST; t_expect_rc unusual 0
grep '^low,' "$D/low/floors.csv" | grep -q 'units = m/s2 gives a horizontal ZPA of 0.0306 g, unusual' && t_pass ||
  t_fail "floors.csv: the unusual-ZPA warning: $(grep '^low,' "$D/low/floors.csv" | head -c 300)"
if command -v python3 >/dev/null 2>&1; then
  python3 - "$D/acc/seislide-clearance.xlsx" "$D/low/seislide-clearance.xlsx" > "$D/check.txt" 2>&1 <<'PY'
import sys, zipfile, re
def book(path):
    z = zipfile.ZipFile(path)
    wb = z.read('xl/workbook.xml').decode()
    rels = z.read('xl/_rels/workbook.xml.rels').decode()
    sheets = re.findall(r'<sheet name="([^"]+)" sheetId="\d+"(?: state="hidden")? r:id="(rId\d+)"', wb)
    target = dict(re.findall(r'Id="(rId\d+)"[^>]*Target="([^"]+)"', rels))
    target.update({k: v for v, k in re.findall(r'Target="([^"]+)"[^>]*Id="(rId\d+)"', rels)})
    ss = re.findall(r'<si><t[^>]*>(.*?)</t></si>', z.read('xl/sharedStrings.xml').decode(), re.S)
    xml = {name: z.read('xl/' + target[rid]).decode() for name, rid in sheets}
    def cell(name, ref):
        m = re.search(r'<c r="%s"[^>]*t="s"[^>]*><v>(\d+)</v>' % ref, xml[name])
        return ss[int(m.group(1))] if m else ''
    def strings(name):
        return [ss[int(v)] for v in re.findall(r't="s"[^>]*><v>(\d+)</v>', xml[name])]
    return cell, strings
def ok(cond, what):
    print(('ok ' if cond else 'FAIL ') + what)
for path, want in ((sys.argv[1], '01-ground: accepted by --accept-floor: horizontal ZPA 2.94 g'),
                   (sys.argv[2], 'low: units = m/s2 gives a horizontal ZPA of 0.0306 g')):
    cell, strings = book(path)
    for sheet in ('Lookup', 'Summary'):  # the line under the title block (row 9)
        ok(want in cell(sheet, 'A9') and cell(sheet, 'A9').startswith('WARNINGS'), '%s: %s A9: %s' % (path, sheet, cell(sheet, 'A9')[:160]))
    ok(any(want.split(': ', 1)[1] in s for s in strings('Notes')), path + ': Notes')
cell, strings = book(sys.argv[1])
inputs = strings('Inputs')
i = [k for k, s in enumerate(inputs) if s == 'accepted floors']
ok(i and inputs[i[0] + 1] == '01-ground (--accept-floor)', 'Inputs: the accepted floor: %s' % inputs[i[0]:i[0] + 2] if i else 'no entry')
cell, strings = book(sys.argv[2])
inputs = strings('Inputs')
i = [k for k, s in enumerate(inputs) if s == 'accepted floors']
ok(i and inputs[i[0] + 1] == 'none', 'Inputs: no floor accepted')
PY
  grep -q '^FAIL' "$D/check.txt" && t_fail "workbooks: $(grep '^FAIL' "$D/check.txt" | head -5)" || t_pass
  grep -q '^ok' "$D/check.txt" || t_fail "workbooks not read: $(head -c 400 "$D/check.txt")"
else
  t_skip "python3 absent: the workbooks' warning lines are not read"
fi

# a plant run in two shards and merged keeps the accepted floor's warning, as one run has it
mkdir -p "$D/p2/bldA" "$D/p2/bldB"
cp floors/04-roof36.ini "$D/p2/bldA/"; scale floors/01-ground.ini 9.80665 > "$D/p2/bldA/01-ground.ini"
cp floors/01-ground.ini floors/04-roof36.ini "$D/p2/bldB/"
t_run run "$D/p2" -o "$D/whole" $FAST --accept-floor bldA/01-ground; t_expect_rc plant-accepted 0
for k in 1 2; do
  t_run run "$D/p2" -o "$D/parts/$k" $FAST --accept-floor bldA/01-ground --shard $k/2; t_expect_rc shard-$k 0
done
t_run merge "$D/parts/1" "$D/parts/2" -o "$D/merged" --created 1700000000 -q; t_expect_rc merge 0
pw() { grep -v '^#' "$1/plant.csv" | tr -d '\r' | awk -F, 'NR > 1 { print $1 "/" $2 ": " ($0 ~ /accepted by --accept-floor/ ? "warned" : $NF != "" ? "?" : "-") }'; }
same() { grep -v '^# command' "$1" > "$D/x1"; grep -v '^# command' "$2" > "$D/x2"; cmp -s "$D/x1" "$D/x2"; }
[ "$(pw "$D/whole")" = "bldA/01-ground: warned
bldA/04-roof36: -
bldB/01-ground: -
bldB/04-roof36: -" ] && t_pass || t_fail "plant.csv warnings: $(pw "$D/whole" | tr '\n' ' ')"
same "$D/whole/plant.csv" "$D/merged/plant.csv" && same "$D/whole/bldA/floors.csv" "$D/merged/bldA/floors.csv" &&
  t_pass || t_fail "merged outputs differ from one run's: $(diff "$D/whole/plant.csv" "$D/merged/plant.csv" | head -c 400)"
t_end
