#!/bin/sh
# The workbook as a document (issue 15): read its XML (title block, notes,
# protection, named ranges, chart axes and series, the ASCE-below-NLTHA
# ranges agreeing across sheets and CSV), then render it to PDF with
# LibreOffice and check the page count and the floor sheets' print scale.
. "$(dirname "$0")/lib.sh"
t_suite cli_workbook
D=$T_TMP
mkdir -p "$D/floors"
cp floors/01-ground.ini floors/04-roof36.ini "$D/floors/"
t_run run "$D/floors" -o "$D/res" --sets 3 --mu-range 0.05:0.80:0.05 --created 1700000000 -q \
  --project "Plant & Unit 2" --document DOC-0042 --revision C --prepared "A. Author" --checked "B. Checker"
t_expect_rc run 0
# the recorded command line pastes into a shell: a value with blanks or '&' is quoted
grep -q "^# command: seislide run .* --project 'Plant & Unit 2' --document DOC-0042 .* --prepared 'A. Author'" \
  "$D/res/summary.csv" && t_pass || t_fail "command line not shell-quoted: $(grep '^# command' "$D/res/summary.csv")"
if ! command -v python3 >/dev/null 2>&1; then
  t_skip "python3 absent: workbook not inspected"; t_end; exit $?
fi
python3 - "$D/res" > "$D/check.txt" 2>&1 <<'PY'
import sys, zipfile, re, csv, io
d = sys.argv[1]
z = zipfile.ZipFile(d + '/seislide-clearance.xlsx')
wb = z.read('xl/workbook.xml').decode()
rels = z.read('xl/_rels/workbook.xml.rels').decode()
sheets = re.findall(r'<sheet name="([^"]+)" sheetId="\d+"(?: state="hidden")? r:id="(rId\d+)"', wb)
hidden = re.findall(r'<sheet name="([^"]+)" sheetId="\d+" state="hidden"', wb)
target = dict(re.findall(r'Id="(rId\d+)"[^>]*Target="([^"]+)"', rels))
target.update({k: v for v, k in re.findall(r'Target="([^"]+)"[^>]*Id="(rId\d+)"', rels)})
xml = {name: z.read('xl/' + target[rid]).decode() for name, rid in sheets}
ss = re.findall(r'<si><t[^>]*>(.*?)</t></si>', z.read('xl/sharedStrings.xml').decode(), re.S)
ss = [s.replace('&amp;', '&').replace('&lt;', '<').replace('&gt;', '>') for s in ss]
def strings(name):
    return [ss[int(v)] for v in re.findall(r't="s"[^>]*><v>(\d+)</v>', xml[name])]
def ok(cond, what):
    print(('ok ' if cond else 'FAIL ') + what)
names = [n for n, _ in sheets]
floors = names[2:-4]
ok(names[:2] == ['Lookup', 'Summary'] and names[-4:] == ['Motion quality', 'Notes', 'Inputs', 'Data'] and len(floors) == 2, 'sheets ' + '|'.join(names))
# floor sheets named by the floor ids, the full name in their title; Data hidden (not printed)
ok(floors == ['01-ground', '04-roof36'], 'floor sheets named by id: %s' % floors)
ok(hidden == ['Data'], 'Data hidden: %s' % hidden)
ok(any(t.startswith('Floor 04-roof36: Roof el. 36 m') for t in strings('04-roof36')), 'full name in the floor sheet title')
# every CSV traces its run: command, created, seed, and each floor file's CRC-32 as Inputs gives it
import glob
inputs = strings('Inputs')
for f in sorted(glob.glob(d + '/*.csv')):
    head = [l for l in open(f, newline='').read().split('\r\n') if l.startswith('#')]
    keys = [l.split(':')[0] for l in head]
    ok(all(k in keys for k in ('# program', '# command', '# created', '# seed', '# floor_file_crc32')), f + ' comment lines: %s' % keys)
    ok('# created: 2023-11-14T22:13:20Z' in head and '# seed: 1' in head and any('--created 1700000000' in l for l in head if l.startswith('# command')), f + ' created, seed, command')
    for l in head:
        if l.startswith('# floor_file_crc32: '):
            c = l.split()[2]
            ok(c in inputs, f + ' CRC-32 %s as on Inputs' % c)
# title block on Lookup and Summary
for n in ('Lookup', 'Summary'):
    s = strings(n)
    ok(all(x in s for x in ('Project', 'Plant & Unit 2', 'Document no.', 'DOC-0042', 'Revision', 'C', 'Prepared by', 'A. Author', 'Checked by', 'B. Checker', 'Date', '2023-11-14')), 'title block on ' + n)
# notes: the assumptions named
notes = ' '.join(strings('Notes'))
for k in ('rigid block', 'Sliding only', 'rocking, overturning', 'static coefficient equal to the kinetic', 'level floor', 'Cap = 1.5', '3 x the mean', '2 x the ASCE', 'standard error'):
    ok(k in notes, 'notes mention ' + k)
# the command on Inputs copies into a shell (issue 42): lines broken between words, each
# but the last ending in " \\", none longer than the cell holds (no option broken at its
# hyphens), the lines together the command summary.csv records
rec = [l[len('# command: '):].rstrip('\r\n') for l in open(d + '/summary.csv') if l.startswith('# command: ')][0]
cmd = [t for t in strings('Inputs') if t.startswith('seislide run')]
ok(len(cmd) == 1 and '\n' in cmd[0] and cmd[0].replace(' \\\n', ' ') == rec and
   all(len(l) <= 70 and (l.endswith(' \\') or i == len(cmd[0].split('\n')) - 1) for i, l in enumerate(cmd[0].split('\n'))),
   'Inputs: the command in lines that copy: %r' % cmd[:1])
# protection everywhere; on Lookup only the two inputs are unlocked
for n in names:
    ok('<sheetProtection' in xml[n] and 'password' not in xml[n], 'protected without password: ' + n)
styles = z.read('xl/styles.xml').decode()
xfs = re.search(r'<cellXfs[^>]*>(.*?)</cellXfs>', styles, re.S).group(1)
xf = re.findall(r'<xf [^>]*?(?:/>|>.*?</xf>)', xfs, re.S)
unlocked = {i for i, x in enumerate(xf) if 'locked="0"' in x}
cells = re.findall(r'<c r="([A-Z]+\d+)" s="(\d+)"', xml['Lookup'])
ok(sorted(r for r, s in cells if int(s) in unlocked) == ['B11', 'B12'], 'Lookup inputs unlocked: %s' % sorted(r for r, s in cells if int(s) in unlocked))
ok('type="list"' in xml['Lookup'] and 'floor_names' in xml['Lookup'] and 'type="decimal"' in xml['Lookup'], 'Lookup validation')
# named ranges
for nm in ('mu_grid', 'clearance_mm', 'floor_zpa_g'):
    ok(re.search(r'<definedName name="%s">Summary!' % nm, wb) is not None, 'named range ' + nm)
# the names whole (the Summary's headings break them into lines): on the hidden Data sheet
ok(re.search(r'<definedName name="floor_names">Data!', wb) is not None, 'named range floor_names')
ok('Roof el. 36 m' in strings('Data') and not any('\n' in t for t in strings('Data')[:3]), 'floor names whole on Data')
# no C function named in what the workbook shows
ok(not any(re.search(r'\bsl_[a-z_]+', t) for t in ss), 'no C name in the workbook: %s' % [t for t in ss if 'sl_' in t][:2])
# the repeated header row is the table's, and the table is the last part of its sheet: the
# last manual page break is at its header (print titles repeat from the page after)
for i, n in enumerate(names):
    m = re.search(r'<definedName name="_xlnm.Print_Titles" localSheetId="%d">[^<]*\$(\d+):\$(\d+)<' % i, wb)
    if m:
        brk = [int(b) for b in re.findall(r'<brk id="(\d+)"', xml[n])]
        ok(max(brk or [0]) == (int(m.group(1)) - 1 if brk else 0), n + ': header row %s repeated, last page break %s' % (m.group(1), brk))
# column headings over numbers: broken into lines, right-aligned, none longer than its column holds
heads = [t for t in strings('Summary') if t.replace('\n', ' ').replace('\u00a0', ' ') in ('Ground level (RG 1.60, 0.3 g)', 'Roof el. 36 m')]
ok(len(heads) == 2 and '\n' in heads[0] and all(len(l) <= 13 for t in heads for l in t.split('\n')), 'Summary headings broken into lines of 13 characters at most (a column 12 wide): %s' % heads)
# charts: one per floor + Summary; x = mu on the same axis limits, log y with the same limits
charts = sorted(n for n in z.namelist() if re.match(r'xl/charts/chart\d+\.xml$', n))
ok(len(charts) == 3, 'charts %d' % len(charts))
lims = set()
for c in charts:
    x = z.read(c).decode()
    ok('<c:scatterChart>' in x and '<c:logBase val="10"/>' in x, c + ' scatter, log y')
    lims.add(tuple(re.findall(r'<c:(?:max|min) val="([^"]+)"/>', x)))
ok(len(lims) == 1, 'axes shared by every chart: %s' % lims)
ser = [z.read(c).decode().count('<c:ser>') for c in charts]
ok(ser[0] == 2, 'Summary chart: a series per floor (%d)' % ser[0])
ok(all(s >= 4 for s in ser[1:]), 'floor charts: design, ASCE, mean, cap, bands (%s)' % ser)
# the ASCE-below-NLTHA ranges: CSV, Summary and floor sheet agree
rows = [r for r in csv.reader(io.StringIO(open(d + '/asce_below_nltha.csv').read())) if r and not r[0].startswith('#')][1:]
fl = [r for r in csv.reader(io.StringIO(open(d + '/floors.csv').read())) if r and not r[0].startswith('#')][1:]
for i, f in enumerate(fl):
    rr = [r for r in rows if r[0] == f[0]]
    text = ', '.join('%s%.3f-%.3f%s' % ('<=' if r[6] == '1' else '', float(r[2]), float(r[3]), '+' if r[7] == '1' else '') for r in rr) or 'none'
    ok(int(f[7]) == len(rr), f[0] + ': ranges counted in floors.csv')
    # the sheets print 3 decimals of the exact ends, the CSV 4: compare numbers, not text
    def ranges_in(sheet):
        pat = re.compile(r'^(?:<=)?\d\.\d{3}-\d\.\d{3}\+?(?:, (?:<=)?\d\.\d{3}-\d\.\d{3}\+?)*$|^none$')
        return [t for t in strings(sheet) if pat.match(t)]
    def same(t):
        if text == 'none' or t == 'none':
            return t == text
        a = [float(x) for x in re.findall(r'\d\.\d+', t)]
        b = [float(x) for y in rr for x in (y[2], y[3])]
        return len(a) == len(b) and all(abs(x - y) <= 6e-4 for x, y in zip(a, b)) and \
            t.count('<=') == text.count('<=') and t.count('+') == text.count('+')
    ok(any(same(t) for t in ranges_in('Summary')) and any(same(t) for t in ranges_in(floors[i])), f[0] + ': ranges "%s" on Summary and its sheet' % text)
    cross = 'none' if f[5] == 'none' else None
    if cross:
        ok(any(s.startswith('none') for s in strings('Summary')) and any(s.startswith('none') for s in strings(floors[i])), f[0] + ': crossover none everywhere')
    else:
        ok(any(('mu %.3f' % float(f[5])) in s for s in strings(floors[i])), f[0] + ': crossover on its sheet')
# print setup: portrait floor sheets at a fixed scale >= 70 %, header and footer with page x of y
for n in floors:
    m = re.search(r'<pageSetup[^>]*scale="(\d+)"', xml[n])
    ok(m is not None and int(m.group(1)) >= 70 and 'fitToPage' not in xml[n] and 'orientation="portrait"' in xml[n], n + ' print scale %s' % (m and m.group(1)))
for n in names:
    ok('Page &amp;P of &amp;N' in xml[n] and '<oddHeader>' in xml[n], n + ' header and footer')
    ok('Project: Plant &amp;&amp; Unit 2' in xml[n] and '(--' not in xml[n].split('<oddHeader>')[1].split('</oddHeader>')[0] and 'Document DOC-0042, revision C' in xml[n] and '&amp;C' not in xml[n].split('<oddHeader>')[1].split('</oddHeader>')[0], n + ' header: title block left, nothing centred')
PY
grep '^FAIL' "$D/check.txt" | while read -r l; do echo "  FAIL cli_workbook: $l" >&2; done
np=$(grep -c '^ok ' "$D/check.txt"); nf=$(grep -c '^FAIL' "$D/check.txt")
[ "$np" -gt 40 ] && [ "$nf" -eq 0 ] && t_pass || t_fail "workbook checks: $np ok, $nf failed ($(grep -v '^ok ' "$D/check.txt" | head -5))"

# render to PDF: Lookup 1 page, Summary 4 (chart; the floors' records, two pages since a
# record is never split across pages and these two do not fit on one; table), each floor 2
# (table at 72 %, chart), Motion quality 1 (one row per set), Notes 2 (its paragraphs in rows
# tall enough to show them whole), Inputs 1; Data is hidden: 13 pages for two floors
if command -v soffice >/dev/null 2>&1; then
  (cd "$D" && timeout 180 soffice -env:UserInstallation=file://$D/lo --headless --convert-to pdf --outdir pdf res/seislide-clearance.xlsx >/dev/null 2>&1)
  if [ -s "$D/pdf/seislide-clearance.pdf" ]; then
    t_pass
    pages=$(python3 -c "import re,sys; print(len(re.findall(rb'/Type\s*/Page[^s]', open(sys.argv[1], 'rb').read())))" "$D/pdf/seislide-clearance.pdf")
    [ "$pages" -eq 13 ] && t_pass || t_fail "PDF has $pages pages, expected 13 (a sheet spilled over its page width?)"
    # a table's header row is printed only over its rows: every page that shows a heading
    # line starting "mu" shows rows of the table under it
    if command -v pdftotext >/dev/null 2>&1; then
      pdftotext -layout "$D/pdf/seislide-clearance.pdf" "$D/pdf/text.txt"
      bad=$(python3 - "$D/pdf/text.txt" <<'PY'
import sys, re
bad = []
for i, p in enumerate(open(sys.argv[1]).read().split('\f')[:-1], 1):
    lines = p.split('\n')
    head = [l for l in lines if re.match(r'\s*mu\s+(mu g|Ground|Roof)', l)]
    rows = [l for l in lines if re.match(r'\s*0\.\d\d\s+[\d.]+\s+[\d.]+', l)]
    if head and len(rows) < 5:
        bad.append(i)
print(' '.join(map(str, bad)))
PY
)
      [ -z "$bad" ] && t_pass || t_fail "table header printed over pages without table rows: $bad"
    fi
  else
    t_fail "soffice did not render the workbook to PDF"
  fi
else
  t_skip "soffice (LibreOffice) not found: the workbook is not rendered; install libreoffice-calc-nogui"
fi
t_end
