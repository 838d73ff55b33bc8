#!/bin/sh
# The workbook as printed (issue 25): render it through LibreOffice headless to
# PDF and read the PDF's word boxes (pdftotext -bbox, poppler-utils):
#  - the page count of the example facility;
#  - every word inside the page's margins, no two words overprinting each
#    other (text cut at a cell's edge or wrapped into a row too short for it
#    lands on its neighbour), no word split inside (every word printed is a
#    word of the workbook's own text: "correlatio" + "n" is not);
#  - the Notes give every floor its own number of motion sets (from
#    floors.csv), and the Lookup's policy text the chosen floor's.
# A coarse grid and loose targets keep it under 40 s while the floors still
# stop at different counts. Skipped without soffice, pdftotext or python3.
. "$(dirname "$0")/lib.sh"
t_suite cli_pdf
D=$T_TMP
for tool in soffice pdftotext python3; do
  if ! command -v $tool >/dev/null 2>&1; then
    t_skip "$tool absent: the printed workbook is not checked (apt-get install libreoffice-calc-nogui poppler-utils python3)"
    t_end; exit $?
  fi
done
t_run run floors -o "$D/res" --rel-se 0.3 --abs-se 5 --max-sets 30 --mu-range 0.05:0.80:0.05 \
  --created 1700000000 -q --project "Unit 3 Reactor Building seismic clearance of unanchored components" \
  --document CALC-RB-0042-S --revision B
t_expect_rc run 0
(cd "$D" && timeout 180 soffice -env:UserInstallation=file://$D/lo --headless --convert-to pdf \
  --outdir pdf res/seislide-clearance.xlsx >/dev/null 2>&1)
if [ ! -s "$D/pdf/seislide-clearance.pdf" ]; then
  t_fail "soffice did not render the workbook to PDF"; t_end; exit $?
fi
pdftotext -bbox "$D/pdf/seislide-clearance.pdf" "$D/words.html"
pdftotext -layout "$D/pdf/seislide-clearance.pdf" "$D/text.txt"
python3 - "$D/res" "$D/words.html" "$D/text.txt" > "$D/check.txt" 2>&1 <<'PY'
import sys, re, zipfile, csv, io, html
res, words_html, text_txt = sys.argv[1:4]
def ok(cond, what):
    print(('ok ' if cond else 'FAIL ') + what)
# Lookup 1, Summary 4 (table, each floor's statements, chart), each floor 2
# (table, chart), Motion quality 1 (one row per set: 46 sets here, 10-16 a
# floor; 50 sets took 2 pages), Notes 2, Inputs 1; Data
# hidden (it printed as one more, unreadable page)
EXPECTED_PAGES = 17
MARGIN_LR = 36.0   # 0.5 in (layout.c)
SLACK = 1.5        # points
pages = []
for m in re.finditer(r'<page width="([\d.]+)" height="([\d.]+)">(.*?)</page>', open(words_html).read(), re.S):
    w = [(float(a), float(b), float(c), float(e), html.unescape(t)) for a, b, c, e, t in
         re.findall(r'<word xMin="([\d.]+)" yMin="([\d.]+)" xMax="([\d.]+)" yMax="([\d.]+)">(.*?)</word>', m.group(3))]
    pages.append((float(m.group(1)), float(m.group(2)), w))
ok(len(pages) == EXPECTED_PAGES, 'pages %d, expected %d' % (len(pages), EXPECTED_PAGES))
# every word within the left and right margins
for p, (pw, ph, ws) in enumerate(pages, 1):
    out = [t for x0, y0, x1, y1, t in ws if x0 < MARGIN_LR - SLACK or x1 > pw - MARGIN_LR + SLACK]
    ok(not out, 'page %d: words beyond the margins: %s' % (p, out[:5]))
# no two words overprint (boxes overlapping by more than a quarter of the smaller)
for p, (pw, ph, ws) in enumerate(pages, 1):
    grid = {}
    for i, (x0, y0, x1, y1, t) in enumerate(ws):
        for gx in range(int(x0 // 20), int(x1 // 20) + 1):
            for gy in range(int(y0 // 20), int(y1 // 20) + 1):
                grid.setdefault((gx, gy), []).append(i)
    bad = set()
    for cell in grid.values():
        for a in range(len(cell)):
            for b in range(a + 1, len(cell)):
                A, B = ws[cell[a]], ws[cell[b]]
                ix = min(A[2], B[2]) - max(A[0], B[0]); iy = min(A[3], B[3]) - max(A[1], B[1])
                if ix > 0 and iy > 0:
                    small = min((A[2] - A[0]) * (A[3] - A[1]), (B[2] - B[0]) * (B[3] - B[1]))
                    if ix * iy > 0.25 * small:
                        bad.add('%s/%s' % (A[4], B[4]))
    ok(not bad, 'page %d: overprinted words: %s' % (p, sorted(bad)[:6]))
# no word split inside: every printed word with letters is a word of the workbook
z = zipfile.ZipFile(res + '/seislide-clearance.xlsx')
text = []
for n in z.namelist():
    if n.endswith('.xml'):
        x = z.read(n).decode()
        text += re.findall(r'<(?:t|a:t|c:v|v|oddHeader|oddFooter)[^>]*>([^<]*)<', x)
tokens = set()
strip = '.,;:()[]|\'"*'
for s in text:
    s = html.unescape(html.unescape(s))
    s = re.sub(r'&(?:\d+|[LCRAPNF]|"[^"]*")', ' ', s)
    for t in s.split():
        t = t.strip(strip)
        tokens.add(t)
        tokens.update(x.strip(strip) for x in re.split(r'(?<=[-/])', t))
tokens.update(['Page', 'of', 'seislide-clearance.xlsx'])
split = set()
for p, (pw, ph, ws) in enumerate(pages, 1):
    for x0, y0, x1, y1, t in ws:
        u = t.strip(strip)
        if re.search(r'[A-Za-z]', u) and u not in tokens and not re.fullmatch(r'[-+\d.,E]+', u):
            split.add('p%d:%s' % (p, t))
ok(not split, 'words not in the workbook (split or cut): %s' % sorted(split)[:10])
# Notes and Lookup: every floor's own number of sets
fl = [r for r in csv.reader(io.StringIO(open(res + '/floors.csv', newline='').read())) if r and not r[0].startswith('#')]
col = fl[0].index('n_sets')
sets = {r[0]: int(r[col]) for r in fl[1:]}
ok(len(set(sets.values())) > 1, 'the floors stop at different counts: %s' % sets)
pt = open(text_txt).read().split('\f')
notes = ' '.join(' '.join(p.split()) for p in pt if re.search(r'^\s*Notes\s*$', p[:600], re.M))
for fid, n in sets.items():
    pat = re.escape(fid).replace('\\-', '-\\s?')
    a = re.findall(pat + r':\s(\d+) sets', notes)
    b = re.findall(pat + r'\ssd/\s?sqrt\((\d+)\)', notes)
    ok(a == [str(n)] and b == [str(n)], 'Notes: %s %s sets, sd/sqrt(%s); floors.csv %d' % (fid, a, b, n))
ok(not re.search(r'\d+ sets per floor', notes), 'Notes: no one count for every floor')
lookup = ' '.join(pt[0].split())
first = fl[1][0]
ok(('of %d synthesized motion sets of this floor' % sets[first]) in lookup, 'Lookup policy: %s has %d sets' % (first, sets[first]))
PY
grep '^FAIL' "$D/check.txt" | while read -r l; do echo "  FAIL cli_pdf: $l" >&2; done
np=$(grep -c '^ok ' "$D/check.txt"); nf=$(grep -c '^FAIL' "$D/check.txt")
[ "$np" -gt 30 ] && [ "$nf" -eq 0 ] && t_pass || t_fail "printed workbook: $np ok, $nf failed ($(grep -v '^ok ' "$D/check.txt" | head -3))"
t_end
