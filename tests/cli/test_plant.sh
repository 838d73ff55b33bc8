#!/bin/sh
# End-to-end tests of plant runs (docs/plant.md): a folder of buildings, the
# per-building outputs and the plant index against per-building runs, the
# floor-result cache (reuse, one floor changed, SIGKILL and resume, a damaged
# entry, two runs sharing one cache), shards through GNU parallel and merge.
. "$(dirname "$0")/lib.sh"
t_suite cli_plant
D=$T_TMP
B="$SEISLIDE_BIN"
mkdir -p "$D/plant/bldA" "$D/plant/bldB" "$D/parts"
cp floors/01-ground.ini floors/02-el12.ini "$D/plant/bldA/"
# the same floor file name in two buildings is fine; so is the same floor
cp floors/01-ground.ini floors/04-roof36.ini "$D/plant/bldB/"
OPTS="--sets 2 --mu 0.05,0.1,0.2,0.3,0.5 --created 1700000000"
# the same CSV file apart from the recorded command line (which names the
# output folder and the options; issue 23: byte-identical apart from it)
csv_same() {
  cmp -s "$1" "$2" && return 0
  grep -v '^# command: ' "$1" > "$T_TMP/csv_a"; grep -v '^# command: ' "$2" > "$T_TMP/csv_b"
  cmp -s "$T_TMP/csv_a" "$T_TMP/csv_b"
}
# same outputs: the same files, every CSV byte for byte but for its command
# line (the workbooks record it too)
same_out() {
  [ "$(cd "$1" && find . -path ./.seislide-cache -prune -o -type f -print | sort)" = \
    "$(cd "$2" && find . -path ./.seislide-cache -prune -o -type f -print | sort)" ] || return 1
  for f in $(cd "$2" && find . -name '*.csv'); do csv_same "$1/$f" "$2/$f" || return 1; done
}

t_run run "$D/plant" -o "$D/out1" $OPTS; t_expect_rc plant-run 0
for f in plant.csv plant.xlsx bldA/seislide-clearance.xlsx bldA/summary.csv \
         bldA/floor_01-ground.csv bldA/floor_02-el12.csv bldB/floor_01-ground.csv \
         bldB/floor_04-roof36.csv bldB/motion_quality.csv; do
  [ -s "$D/out1/$f" ] && t_pass || t_fail "missing output $f"
done
[ -e "$D/out1/seislide-clearance.xlsx" ] && t_fail "a plant has no top-level building workbook" || t_pass
# bldB/01-ground is bldA/01-ground (the same numbers): computed once, then reused
t_expect_err progress-per-floor "floor 3/4 'bldB/01-ground' reused from the cache; 3/4 floors done \(1 reused\), 6 sets"
t_expect_err progress-per-floor "floor 4/4 'bldB/04-roof36' computed; 4/4 floors done \(1 reused\), 8 sets, elapsed [0-9:]+, ETA"
[ "$(grep -v '^#' "$D/out1/plant.csv" | wc -l)" -eq 5 ] && t_pass || t_fail "plant.csv: header + 4 rows expected"
grep -v '^#' "$D/out1/plant.csv" | head -1 | grep -q '^building,floor,floor_name,elevation_m,zpa_g,sets,convergence,clearance_mm_mu_0.05,clearance_mm_mu_0.1,clearance_mm_mu_0.2,clearance_mm_mu_0.3,clearance_mm_mu_0.4,clearance_mm_mu_0.5,governing' && t_pass || t_fail "plant.csv header"
[ "$(head -1 "$D/out1/plant.csv" | tail -c 2 | od -An -c | tr -d ' ')" = '\r\n' ] && t_pass || t_fail "plant.csv: CRLF line ends"

# plant.csv traces its run as every building CSV does (issue 25): # program:
# first, then command, created, seed, and each floor file's CRC-32 line, the
# building's own line with the floor named building/id
head -1 "$D/out1/plant.csv" | grep -q '^# program: seislide ' && t_pass || t_fail "plant.csv: '# program:' not first"
for l in '# command: seislide run .*-o [^ ]*/out1 .*/plant' '# created: 2023-11-14T22:13:20Z' '# seed: 1' '# project: -'; do
  grep -q "^$l" "$D/out1/plant.csv" && t_pass || t_fail "plant.csv lacks /$l/"
done
[ "$(grep -c '^# floor_file_crc32: ' "$D/out1/plant.csv")" -eq 4 ] && t_pass || t_fail "plant.csv: 4 floor_file_crc32 lines expected"
for b in bldA bldB; do
  grep '^# floor_file_crc32: ' "$D/out1/$b/summary.csv" | sed "s|^\(# floor_file_crc32: [0-9a-f]*\) |\1 $b/|" |
    while IFS= read -r l; do grep -qxF "$l" "$D/out1/plant.csv" || echo "$l"; done > "$D/crc_missing"
  [ -s "$D/crc_missing" ] && t_fail "plant.csv lacks $(head -1 "$D/crc_missing")" || t_pass
done

# plant.xlsx as printed (issue 25), through LibreOffice and pdftotext -bbox:
# Data hidden; the Lookup one portrait page at 100 %, the range of mu under
# its input; the Plant sheet one landscape page; every word inside the
# margins, at a readable size, none overprinting another; the page header
# and footer of the building workbook on each page
if command -v python3 >/dev/null 2>&1; then
python3 - "$D/out1/plant.xlsx" > "$D/hidden.txt" 2>&1 <<'PY'
import sys, zipfile, re
w = zipfile.ZipFile(sys.argv[1]).read('xl/workbook.xml').decode()
s = {m.group(1): m.group(0) for m in re.finditer(r'<sheet name="([^"]*)"[^>]*>', w)}
print('ok' if 'state="hidden"' in s.get('Data', '') and not any('hidden' in v for k, v in s.items() if k != 'Data') else 'FAIL %s' % s)
PY
[ "$(cat "$D/hidden.txt")" = ok ] && t_pass || t_fail "plant.xlsx: Data must be the one hidden sheet: $(cat "$D/hidden.txt")"
fi
if command -v soffice >/dev/null 2>&1 && command -v pdftotext >/dev/null 2>&1 && command -v python3 >/dev/null 2>&1; then
  (cd "$D" && timeout 180 soffice -env:UserInstallation=file://$D/lo --headless --convert-to pdf \
    --outdir pdf out1/plant.xlsx >/dev/null 2>&1)
  pdftotext -bbox "$D/pdf/plant.pdf" "$D/plant_words.html" 2>/dev/null
  python3 - "$D/plant_words.html" > "$D/plant_pdf.txt" 2>&1 <<'PY'
import sys, re, html, collections
def ok(cond, what):
    print(('ok ' if cond else 'FAIL ') + what)
MARGIN, SLACK = 36.0, 1.5   # 0.5 in left and right (layout.c), points
pages = []
for m in re.finditer(r'<page width="([\d.]+)" height="([\d.]+)">(.*?)</page>', open(sys.argv[1]).read(), re.S):
    w = [(float(a), float(b), float(c), float(e), html.unescape(t)) for a, b, c, e, t in
         re.findall(r'<word xMin="([\d.]+)" yMin="([\d.]+)" xMax="([\d.]+)" yMax="([\d.]+)">(.*?)</word>', m.group(3))]
    pages.append((float(m.group(1)), float(m.group(2)), w))
# Lookup 1 page, Plant 1 page (4 floors); Data hidden (it printed 12 of 14)
ok(len(pages) == 2, 'pages %d, expected 2' % len(pages))
for p, (pw, ph, ws) in enumerate(pages, 1):
    text = [t for *_, t in ws]
    out = [t for x0, y0, x1, y1, t in ws if x0 < MARGIN - SLACK or x1 > pw - MARGIN + SLACK or y0 < 0 or y1 > ph]
    ok(not out, 'page %d: words beyond the margins: %s' % (p, out[:5]))
    # a word box is about 1.3 x the font size: 7 pt is a 5.4 pt font printed
    small = [t for x0, y0, x1, y1, t in ws if y1 - y0 < 7.0]
    ok(not small, 'page %d: words under 7 pt: %s' % (p, small[:5]))
    top = [t for x0, y0, x1, y1, t in ws if y1 < 60]
    bottom = ' '.join(t for x0, y0, x1, y1, t in ws if y0 > ph - 60)
    ok('Document' in top and 'revision' in top, 'page %d: header without the title block: %s' % (p, top[:8]))
    ok(re.search(r'seislide .*plant\.xlsx Page %d of %d' % (p, len(pages)), bottom) is not None,
       'page %d: footer "%s"' % (p, bottom))
    ok('building|floor' not in text, 'page %d: the Data sheet printed' % p)
    bad = set()
    for i, A in enumerate(ws):
        for B in ws[i + 1:]:
            ix = min(A[2], B[2]) - max(A[0], B[0]); iy = min(A[3], B[3]) - max(A[1], B[1])
            if ix > 0 and iy > 0 and ix * iy > 0.25 * min((A[2] - A[0]) * (A[3] - A[1]), (B[2] - B[0]) * (B[3] - B[1])):
                bad.add('%s/%s' % (A[4], B[4]))
    ok(not bad, 'page %d: overprinted words: %s' % (p, sorted(bad)[:6]))
def body(ws):   # the most common word height: the 11-point text as printed
    return collections.Counter(round(y1 - y0, 1) for x0, y0, x1, y1, t in ws).most_common(1)[0][0]
if len(pages) >= 2:
    (w1, h1, l), (w2, h2, pl) = pages[0], pages[1]
    ok(w1 < h1 and 'Lookup' in [t for *_, t in l], 'page 1: the Lookup, portrait')
    ok(body(l) >= 13.5, 'Lookup printed at about 100 %%: words %.1f pt high, 14.3 at 100 %%' % body(l))
    ok(w2 > h2 and 'Plant' in [t for *_, t in pl], 'page 2: the Plant sheet, landscape')
    ok(body(pl) >= 10.0, 'Plant sheet readable: words %.1f pt high (14.3 at 100 %%)' % body(pl))
    # the range of mu under its input: between the mu row and the result, in column B
    y = {t: (x0, y0) for x0, y0, x1, y1, t in l}
    if all(k in y for k in ('Friction', 'covers', 'Required', 'Input')):
        ok(y['Friction'][1] < y['covers'][1] < y['Input'][1] and y['covers'][0] > y['Friction'][0] + 100,
           'Lookup: the range note under the mu input: %s' % {k: y[k] for k in ('Friction', 'covers', 'Input')})
    else:
        ok(False, 'Lookup: words Friction, covers, Required, Input not all printed')
    rows = sum(1 for *_, t in pl if t in ('bldA', 'bldB'))
    ok(rows == 4, 'Plant sheet: %d floor rows printed, 4 expected' % rows)
PY
  grep "^FAIL" "$D/plant_pdf.txt" | while read -r l; do echo "  FAIL cli_plant: $l" >&2; done
  np=$(grep -c '^ok ' "$D/plant_pdf.txt"); nf=$(grep -c '^FAIL' "$D/plant_pdf.txt")
  [ "$np" -eq 19 ] && [ "$nf" -eq 0 ] && t_pass || t_fail "printed plant.xlsx: $np ok, $nf failed ($(grep -v '^ok ' "$D/plant_pdf.txt" | head -3))"
else
  t_skip "soffice, pdftotext or python3 absent: plant.xlsx as printed not checked (apt-get install libreoffice-calc-nogui poppler-utils)"
fi

# per-building runs (no cache): the same files, byte for byte
for b in bldA bldB; do
  t_run run "$D/plant/$b" -o "$D/single-$b" $OPTS --no-cache -q; t_expect_rc "run $b" 0
  [ ! -e "$D/single-$b/.seislide-cache" ] && t_pass || t_fail "--no-cache wrote a cache"
  [ ! -e "$D/single-$b/plant.csv" ] && t_pass || t_fail "one building writes no plant index"
  for f in "$D/single-$b"/*.csv; do
    csv_same "$f" "$D/out1/$b/$(basename "$f")" && t_pass || t_fail "$b/$(basename "$f") differs from the building run"
  done
  # plant.csv against the building's own floor tables: clearance at mu 0.05, 0.1, 0.2, 0.3, 0.5
  for fl in "$D/single-$b"/floor_*.csv; do
    id=$(basename "$fl" .csv); id=${id#floor_}
    row=$(awk -F, -v b="$b" -v id="$id" '$1 == b && $2 == id' "$D/out1/plant.csv")
    [ -n "$row" ] || { t_fail "plant.csv lacks $b/$id"; continue; }
    res=$(grep -v '^#' "$fl" | awk -F, -v row="$row" '
      NR == 1 { for (i = 1; i <= NF; i++) if ($i == "clearance_mm") c = i; next }
      { v[$1 + 0] = $c }
      END { nr = split(row, r, ","); n = split("0.05 0.1 0.2 0.3 0.5", m, " "); col[1] = nr - 8; col[2] = nr - 7; col[3] = nr - 6; col[4] = nr - 5; col[5] = nr - 3
            bad = 0; for (k = 1; k <= n; k++) { d = r[col[k]] - v[m[k] + 0]; if (d < 0) d = -d
              h = r[col[k]] ~ /\./ ? 0.05 : 0.5  # half the printed step
              if (d > h + 1e-9 || r[col[k]] == "") bad = 1 }
            print bad ? "bad" : "ok" }')
    [ "$res" = ok ] && t_pass || t_fail "plant.csv row of $b/$id disagrees with $fl: $row"
  done
  # plant.csv prints what the standard error supports: at a grid mu, the very text summary.csv
  # shows (the digit of the SE, 1 or 0.1 mm), never 0.001 mm
  res=$(grep -v '^#' "$D/single-$b/summary.csv" | awk -F, -v b="$b" -v plant="$D/out1/plant.csv" '
    { sub(/\r$/, "") }
    NR == 1 { for (i = 2; i <= NF; i++) { id[i] = $i; sub(/_clearance_mm$/, "", id[i]) } nc = NF; next }
    { for (i = 2; i <= nc; i++) s[id[i], $1 + 0] = $i }
    END { n = split("0.05 0.1 0.2 0.3 0.5", m, " "); bad = ""; rows = 0
          while ((getline l < plant) > 0) {
            if (l ~ /^#/ || l ~ /^building,/) continue
            nr = split(l, r, ","); if (r[1] != b) continue
            col[1] = nr - 8; col[2] = nr - 7; col[3] = nr - 6; col[4] = nr - 5; col[5] = nr - 3
            for (k = 1; k <= n; k++) { rows++; if (r[col[k]] != s[r[2], m[k] + 0] || r[col[k]] ~ /\.[0-9][0-9]/) bad = bad " " r[2] "@" m[k] ":" r[col[k]] "/" s[r[2], m[k] + 0] } }
          print (bad == "" && rows == 2 * n) ? "ok" : "bad" bad }')
  [ "$res" = ok ] && t_pass || t_fail "plant.csv clearances of $b not as summary.csv shows them: $res"
done
# a floor's results do not depend on its building (the same file in both)
grep -v '^# floor' "$D/out1/bldA/floor_01-ground.csv" > "$D/ga"
grep -v '^# floor' "$D/out1/bldB/floor_01-ground.csv" > "$D/gb"
cmp -s "$D/ga" "$D/gb" && t_pass || t_fail "the same floor in two buildings gives different tables"

# cache: an unchanged rerun reuses every floor (computes none) and writes the same outputs;
# its speed is measured by make bench-plant, not here
cp -r "$D/out1" "$D/ref"
t_run run "$D/plant" -o "$D/out1" $OPTS; t_expect_rc rerun 0
t_expect_err rerun-reused "reused 4 of 4 floors"
grep -q "computed;" "$T_ERR" && t_fail "rerun computed a floor" || t_pass
same_out "$D/out1" "$D/ref" && t_pass || t_fail "rerun outputs differ from the first run"

# the key holds the numbers, not the file name, floor name, description or elevation
mkdir -p "$D/plant3/other"
sed -e 's/^name = .*/name = Renamed floor/' -e 's/^description = .*/description = moved/' \
    -e 's/^elevation_m = .*/elevation_m = 99/' floors/02-el12.ini > "$D/plant3/other/x.ini"
t_run run "$D/plant3/other" -o "$D/out3" $OPTS --cache "$D/out1/.seislide-cache"; t_expect_rc renamed 0
t_expect_err renamed-reused "reused 1 of 1 floors"
# opening a cache removes the temporary entries of this host's dead processes, never
# those of another host whose name starts with this one's ("node-b" beside "node")
H=$(hostname)
mkdir -p "$D/hostcache"
: > "$D/hostcache/.0123456789abcdef.tmp-$H-b-1-AbCdEf"   # host "$H-b", its pid 1
: > "$D/hostcache/.0123456789abcdef.tmp-$H-999999-AbCdEf" # this host, no such process
t_run run "$D/plant3/other" -o "$D/out3h" $OPTS -q --cache "$D/hostcache"; t_expect_rc hostcache 0
[ -e "$D/hostcache/.0123456789abcdef.tmp-$H-b-1-AbCdEf" ] && t_pass || t_fail "another host's temporary entry removed"
[ ! -e "$D/hostcache/.0123456789abcdef.tmp-$H-999999-AbCdEf" ] && t_pass || t_fail "a dead process's temporary entry kept"
# the same on a host with a long name (40 characters), beside a host whose name differs only
# in its last character: the whole names are compared (in a user and UTS namespace of its own)
LA=seislide-plant-analysis-worker-node-000a; LB=seislide-plant-analysis-worker-node-000b
if unshare -Ur --uts true 2>/dev/null; then
  mkdir -p "$D/hostcache2"
  : > "$D/hostcache2/.0123456789abcdef.tmp-$LB-1-AbCdEf"      # the other host, its pid 1
  : > "$D/hostcache2/.0123456789abcdef.tmp-$LA-999999-AbCdEf" # this host, no such process
  unshare -Ur --uts sh -c 'hostname "$1" && shift && exec "$@"' sh "$LA" \
    "$SEISLIDE_BIN" run "$D/plant3/other" -o "$D/out3l" $OPTS -q --cache "$D/hostcache2" \
    > /dev/null 2>&1 && t_pass || t_fail "run under a long host name"
  [ -e "$D/hostcache2/.0123456789abcdef.tmp-$LB-1-AbCdEf" ] && t_pass || t_fail "long host name: another host's temporary entry removed"
  [ ! -e "$D/hostcache2/.0123456789abcdef.tmp-$LA-999999-AbCdEf" ] && t_pass || t_fail "long host name: a dead process's temporary entry kept"
else
  t_skip "unshare -Ur --uts not permitted here: long host names not checked"
fi

# more buildings than a plant may hold: refused, naming the folder and the limit, nothing written
mkdir -p "$D/many"
i=0; while [ $i -le 256 ]; do mkdir -p "$D/many/b$i"; i=$((i + 1)); done
t_run run "$D/many" -o "$D/out-many" $OPTS -q; t_expect_rc too-many-buildings 1
t_expect_err too-many-msg "many: more than 256 buildings"
[ ! -e "$D/out-many" ] && t_pass || t_fail "too many buildings: output written"
# one number of one floor changed: exactly that floor recomputed
cp -r "$D/plant" "$D/plant2"
sed -i '0,/0.0226/s//0.0227/' "$D/plant2/bldB/04-roof36.ini"
cp -r "$D/out1" "$D/out2"
t_run run "$D/plant2" -o "$D/out2" $OPTS; t_expect_rc changed 0
t_expect_err changed-reused "reused 3 of 4 floors"
[ "$(grep -c 'computed;' "$T_ERR")" -eq 1 ] && grep -q "'bldB/04-roof36' computed" "$T_ERR" && t_pass || t_fail "not exactly the changed floor recomputed: $(grep computed "$T_ERR")"
cmp -s "$D/out2/bldB/floor_04-roof36.csv" "$D/out1/bldB/floor_04-roof36.csv" && t_fail "the changed floor's table did not change" || t_pass
grep -v -e '^# floor_file' -e '^# command: ' "$D/out2/bldA/floor_02-el12.csv" > "$D/u2"
grep -v -e '^# floor_file' -e '^# command: ' "$D/out1/bldA/floor_02-el12.csv" > "$D/u1"
cmp -s "$D/u1" "$D/u2" && t_pass || t_fail "an unchanged floor's table changed"

# a flipped byte in one cache entry (in its payload: a motion check): detected, the floor recomputed and said, outputs the same
E=$(ls "$D/out1/.seislide-cache"/*.slr | head -1)
size=$(wc -c < "$E")
printf '\377' | dd of="$E" bs=1 seek=$((size - 200)) conv=notrunc 2>/dev/null
t_run run "$D/plant" -o "$D/out1" $OPTS; t_expect_rc flipped 0
t_expect_err flipped-said "cache entry .*$(basename "$E") failed its check \(checksum mismatch"
t_expect_err flipped-reused "reused [23] of 4 floors"
same_out "$D/out1" "$D/ref" && t_pass || t_fail "outputs after a damaged entry differ"
# a truncated entry and a foreign file as an entry: never used, never a crash
E=$(ls "$D/out1/.seislide-cache"/*.slr | head -1)
head -c 100 "$E" > "$D/trunc" && cp "$D/trunc" "$E"
t_run run "$D/plant" -o "$D/out1" $OPTS; t_expect_rc truncated 0
t_expect_err truncated-said "failed its check"
same_out "$D/out1" "$D/ref" && t_pass || t_fail "outputs after a truncated entry differ"

# SIGKILL in the middle, then the same command: identical outputs, finished floors reused.
# The kill comes when the first entry is seen; a fast run may have finished by then (the
# outputs are in place): then the rerun reuses every floor. Kills at chosen system calls,
# which cannot race, are tests/cli/test_faults.sh's.
( "$B" run "$D/plant" -o "$D/outk" $OPTS -q & echo $! > "$D/pid"; wait ) 2>/dev/null &
i=0
while [ $i -lt 600 ] && [ "$(ls "$D/outk/.seislide-cache" 2>/dev/null | grep -c '\.slr$')" -lt 1 ]; do
  sleep 0.1; i=$((i + 1))
done
kill -9 "$(cat "$D/pid")" 2>/dev/null; wait
n_done=$(ls "$D/outk/.seislide-cache" 2>/dev/null | grep -c '\.slr$')
finished=no; [ -e "$D/outk/plant.csv" ] && finished=yes
[ "$n_done" -ge 1 ] && { [ $finished = no ] || [ "$n_done" -eq 3 ]; } && t_pass ||
  t_fail "kill: $n_done entries, outputs written: $finished"
t_run run "$D/plant" -o "$D/outk" $OPTS; t_expect_rc resumed 0
# every entry finished before the kill is reused: the 4 floors hold 3 distinct ones (01-ground
# twice), so n_done entries serve n_done or n_done + 1 floors, all 4 exactly when all 3 were done
R=$(sed -n 's/.*reused \([0-9]*\) of 4 floors.*/\1/p' "$T_ERR" | tail -1)
[ -n "$R" ] && [ "$R" -ge "$n_done" ] && [ "$R" -le $((n_done + 1)) ] &&
  { { [ "$R" -eq 4 ] && [ "$n_done" -eq 3 ]; } || { [ "$R" -lt 4 ] && [ "$n_done" -lt 3 ]; }; } &&
  t_pass || t_fail "resumed: $n_done entries before the kill, then ${R:-no} floors reused"
same_out "$D/outk" "$D/ref" && t_pass || t_fail "resumed outputs differ from an uninterrupted run"

# two runs sharing one cache at once: every floor computed once, both outputs right
mkdir "$D/shared"
"$B" run "$D/plant" -o "$D/outs1" $OPTS --cache "$D/shared" 2> "$D/s1.err" &
p1=$!
"$B" run "$D/plant" -o "$D/outs2" $OPTS --cache "$D/shared" 2> "$D/s2.err" &
p2=$!
wait $p1; r1=$?; wait $p2; r2=$?
[ $r1 -eq 0 ] && [ $r2 -eq 0 ] && t_pass || t_fail "shared cache: exit $r1, $r2"
# bldA/01-ground and bldB/01-ground are one entry: 3 distinct floors to compute
[ "$(cat "$D/s1.err" "$D/s2.err" | grep -c 'computed;')" -eq 3 ] && t_pass || t_fail "shared cache: $(cat "$D/s1.err" "$D/s2.err" | grep -c 'computed;') floors computed, 3 expected"
same_out "$D/outs1" "$D/ref" && same_out "$D/outs2" "$D/ref" && t_pass || t_fail "shared cache: outputs differ"
[ "$(ls "$D/shared" | grep -c '\.slr$')" -eq 3 ] && [ -z "$(ls -a "$D/shared" | grep -E 'lock|tmp')" ] && t_pass || t_fail "shared cache: $(ls -a "$D/shared")"

# shards through GNU parallel, then merge: the outputs of the single run
if command -v parallel >/dev/null 2>&1; then
  parallel "$B" run "$D/plant" --shard {}/3 -o "$D/parts/{}" $OPTS -q ::: 1 2 3; r=$?
  [ $r -eq 0 ] && t_pass || t_fail "parallel shards: exit $r"
  t_run merge "$D"/parts/* -o "$D/merged" --created 1700000000; t_expect_rc merge 0
  for f in $(cd "$D/ref" && find . -name '*.csv'); do
    csv_same "$D/merged/$f" "$D/ref/$f" && t_pass || t_fail "merged $f differs from the single run"
  done
  # the merged cache makes a later run into it reuse everything
  t_run run "$D/plant" -o "$D/merged" $OPTS; t_expect_rc after-merge 0
  t_expect_err after-merge-reused "reused 4 of 4 floors"
  t_run merge "$D/parts/1" "$D/parts/3" -o "$D/m2"; t_expect_rc missing 1
  t_expect_err missing-named "shard 2/3 missing"
  t_run merge "$D/parts/1" "$D/parts/2" "$D/parts/2" "$D/parts/3" -o "$D/m2"; t_expect_rc duplicate 1
  t_expect_err duplicate-named "shard 2/3 given twice: .*parts/2 and .*parts/2"
  [ ! -e "$D/m2" ] && t_pass || t_fail "a failed merge wrote outputs"
  # a damaged shard result is refused, naming it
  R=$(ls "$D/parts/1/results"/*.slr | head -1)
  printf '\377' | dd of="$R" bs=1 seek=40 conv=notrunc 2>/dev/null
  t_run merge "$D"/parts/* -o "$D/m3"; t_expect_rc damaged-shard 1
  t_expect_err damaged-shard-named "$(basename "$R").*failed its check"
else
  t_skip "GNU parallel absent (apt-get install parallel): shards not tested"
fi
t_run run "$D/plant" -o "$D/x" $OPTS --cache "$D/no/such/folder"; t_expect_rc unusable-cache 1
t_expect_err unusable-cache-named "no/such/folder: cannot create the cache folder"
[ ! -e "$D/x" ] && t_pass || t_fail "an unusable cache wrote outputs"
t_run run "$D/plant" --shard 4/3 -o "$D/x"; t_expect_rc bad-shard 2
t_run run "$D/plant" --shard 1/2 --motions -o "$D/x"; t_expect_rc shard-motions 2

# on a terminal: one line updated in place (carriage returns), no line per floor
if command -v script >/dev/null 2>&1; then
  script -qc "'$B' run '$D/plant' -o '$D/outt' $OPTS" /dev/null > "$D/tty.txt" 2>&1
  [ "$(tr '\r' '\n' < "$D/tty.txt" | grep -c "$(printf '\033')\[Krun: ")" -ge 4 ] && tr '\r' '\n' < "$D/tty.txt" | grep -q "4/4 floors done (1 reused), 8 sets, elapsed" &&
    ! grep -q "computed;" "$D/tty.txt" && t_pass || t_fail "terminal progress: $(tr '\r' '\n' < "$D/tty.txt" | tail -3)"
else
  t_skip "script (util-linux) absent: terminal progress not tested"
fi

# -q: no progress on stderr (warnings stay: here the one about fewer than 5 sets)
t_run run "$D/plant" -o "$D/out1" $OPTS -q; t_expect_rc quiet 0
[ -z "$(grep -v 'warning' "$T_ERR")" ] && t_pass || t_fail "-q must silence the progress: $(head -c 300 "$T_ERR")"
# make bench-plant's generator (tools/benchplant.c) writes floors the reader accepts
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILDDIR=$(echo "$SEISLIDE_MAKEVARS" | tr ' ' '\n' | sed -n 's/^BUILD=//p'); BUILDDIR=${BUILDDIR:-build}
# shellcheck disable=SC2086
if make -s -C "$ROOT" $SEISLIDE_MAKEVARS LDFLAGS="$SEISLIDE_LDFLAGS" "$BUILDDIR/tools/benchplant" > "$D/bp.make" 2>&1; then
  "$B" synth --rg160 0.3 --count 3 --seed 1 -o "$D/bpground" -q > /dev/null 2>&1
  (cd "$ROOT" && "$BUILDDIR/tools/benchplant" "$D/bpground" 4 "$D/bpplant") > /dev/null 2>&1 ||
    t_fail "benchplant failed"
  t_run run "$D/bpplant" -o "$D/bpout" --sets 2 --mu 0.1,0.3 --no-cache -q
  [ "$T_RC" -eq 0 ] && t_pass || t_fail "a bench-plant floor refused: $(head -c 400 "$T_ERR")"
else
  t_fail "make $BUILDDIR/tools/benchplant: $(head -c 400 "$D/bp.make")"
fi
# names as written (UTF-8) everywhere; only file and folder names made safe: a building
# "Bâtiment réacteur" with a floor file "Niveau −3 m.ini" named "Niveau −3 m"
U="$D/plantu"; RB='Bâtiment réacteur'; NV='Niveau −3 m'
mkdir -p "$U/$RB" "$U/Aux"
sed -e "s/^name = .*/name = $NV/" floors/01-ground.ini > "$U/$RB/$NV.ini"
cp floors/02-el12.ini "$U/Aux/"
t_run run "$U" -o "$D/outu" --sets 2 --mu 0.1,0.3 --created 1700000000 -q; t_expect_rc utf8-run 0
grep -q "^$RB,$NV,$NV,0.000," "$D/outu/plant.csv" && t_pass || t_fail "plant.csv: building and floor not as written: $(grep -v '^#' "$D/outu/plant.csv" | tail -1)"
grep -q '__' "$D/outu/plant.csv" && t_fail "plant.csv holds a mangled name" || t_pass
[ -s "$D/outu/Bâtiment_réacteur/floor_Niveau_−3_m.csv" ] && t_pass || t_fail "file names: $(cd "$D/outu" && find . -name '*.csv' | tr '\n' ' ')"
grep -q "^# floor_id: $NV" "$D/outu/Bâtiment_réacteur/floor_Niveau_−3_m.csv" && t_pass || t_fail "floor CSV: id not as written"
grep -q "^\"*$NV\"*,$NV," "$D/outu/Bâtiment_réacteur/floors.csv" && t_pass || t_fail "floors.csv: id not as written"
if command -v python3 >/dev/null 2>&1; then
python3 - "$D/outu" "$RB" "$NV" > "$D/utf8.txt" 2>&1 <<'PY'
import sys, zipfile, re, html
d, rb, nv = sys.argv[1:4]
def ok(cond, what):
    print(('ok ' if cond else 'FAIL ') + what)
def book(path):
    z = zipfile.ZipFile(path)
    wb = html.unescape(z.read('xl/workbook.xml').decode())
    ss = [html.unescape(s) for s in re.findall(r'<si><t[^>]*>(.*?)</t></si>', z.read('xl/sharedStrings.xml').decode(), re.S)]
    xml = {n: html.unescape(z.read(n).decode()) for n in z.namelist() if n.startswith('xl/worksheets/sheet')}
    return wb, ss, xml
wb, ss, xml = book(d + '/Bâtiment_réacteur/seislide-clearance.xlsx')
names = re.findall(r'<sheet name="([^"]+)"', wb)
ok(nv in names, 'building workbook: floor sheet named as written: %s' % names)
ok(nv in ss, 'building workbook: the floor name in the Lookup list (Summary)')
pw, pss, pxml = book(d + '/plant.xlsx')
ok(rb in pss and nv in pss, 'plant.xlsx: building and floor names as written')
ok(not any('__' in s for s in pss + ss), 'no mangled name in either workbook')
# the Lookup drop-downs list the names the building Lookup lists: Data column B holds names
ok(rb + '|' + nv in pss, 'plant Lookup keys building|floor name: %s' % [s for s in pss if '|' in s])
ok('Aux|02-el12' not in pss and any(s.startswith('Aux|Elevation') or s.startswith('Aux|') and s != 'Aux|02-el12' for s in pss), 'plant Lookup lists names, not ids: %s' % [s for s in pss if '|' in s])
# page headers: "Project: not given", no command-line flags; no C names in any text
for x in list(xml.values()) + list(pxml.values()):
    h = re.search(r'<oddHeader>(.*?)</oddHeader>', x, re.S)
    ok(h is not None and 'Project: not given' in h.group(1) and '(--' not in h.group(1), 'header: %s' % (h and h.group(1)))
ok(not any(re.search(r'\bsl_[a-z_]+', s) for s in ss + pss), 'no C function named in the workbooks')
PY
grep '^FAIL' "$D/utf8.txt" | while read -r l; do echo "  FAIL cli_plant: $l" >&2; done
[ "$(grep -c '^ok ' "$D/utf8.txt")" -gt 8 ] && ! grep -q '^FAIL' "$D/utf8.txt" && t_pass || t_fail "names as written: $(grep -v '^ok ' "$D/utf8.txt" | head -3)"
fi
t_end
