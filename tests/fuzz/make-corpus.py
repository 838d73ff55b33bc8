#!/usr/bin/env python3
"""make-corpus.py - (re)make the seed corpus of the fuzz targets, tests/fuzz/corpus/NAME/,
from the project's own files (templates/, floors/, tests/data/) and a few small
hand-made agency-format files (formats.h layouts). Never from ../shared/records
(those are not ours to copy). Each seed is the selector byte of the target
(fuzz_floor.c, fuzz_motion.c) followed by the file's bytes.

    python3 tests/fuzz/make-corpus.py      # from the repository root
"""
import glob, hashlib, os, shutil

root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
os.chdir(root)
out = "tests/fuzz/corpus"


def put(target, sel, data):
    d = os.path.join(out, target)
    os.makedirs(d, exist_ok=True)
    blob = bytes([sel]) + data
    name = hashlib.sha1(blob).hexdigest()[:16]
    with open(os.path.join(d, name), "wb") as f:
        f.write(blob)


def read(p):
    with open(p, "rb") as f:
        return f.read()


shutil.rmtree(out, ignore_errors=True)

# fuzz_floor: 0 = INI, 1 = CSV
for p in sorted(glob.glob("templates/*.ini") + glob.glob("floors/*.ini") +
                glob.glob("tests/data/floors/*.ini")):
    put("fuzz_floor", 0, read(p))
for p in sorted(glob.glob("templates/*.csv") + glob.glob("floors/*.csv") +
                glob.glob("tests/data/floors/*.csv")):
    put("fuzz_floor", 1, read(p))
put("fuzz_floor", 1, b"# name: tiny\n# units: g\n# h2: same_as_h1\n"
    b"f_hz,h1_5,h1_10,v_5\r\n0.5,0.2,0.15,0.1\r\n5,1.0,0.8,0.5\r\n50,0.3,0.3,0.2\r\n")
put("fuzz_floor", 1, b"\xef\xbb\xbf# name: \"quoted, name\"\n# units: m/s2\n# elevation_m: 12.5\n"
    b"# building: RB\n# zpa_h1: 2.9\nf_hz,h1_5,h2_5,v_2,\"v_5\"\n1,5,5,3,2.5\n10,9,8,4,3\n"
    b"33,3,3,2,2\n")

# fuzz_motion: 0 AT2 (auto), 1 text (auto, g, dt 0.01), 2 CSV, 3 two columns (cm/s2),
# 4 one column (m/s2, dt 0.005), 5 GeoNet V2A / CSMIP V2, 6 USGS SMC, 7 CWA .acc
for p in sorted(glob.glob("tests/data/motion/*")):
    ext = os.path.splitext(p)[1].lower()
    data = read(p)
    sel = {".at2": 0, ".csv": 2}.get(ext, 1)
    put("fuzz_motion", sel, data)
    if sel == 1:
        put("fuzz_motion", 3, data)
        put("fuzz_motion", 4, data)
for p in sorted(glob.glob("tests/data/example/*")):
    put("fuzz_motion", 1, read(p))

vals = [0.01 * ((k * 37) % 21 - 10) for k in range(24)]


def fixed(values, per, width, fmt):
    lines = []
    for i in range(0, len(values), per):
        lines.append("".join(fmt % v for v in values[i:i + per]))
    return "\n".join(lines) + "\n"


# CSMIP V2, two channels
v2 = ""
for ch, name in ((1, "90 Deg"), (2, "Up")):
    v2 += "Corrected accelerogram   Chan %d: %s\n" % (ch, name)
    v2 += "Station No. 24000\nChan %d: %s\n" % (ch, name)
    v2 += "%d points of accel data equally spaced at  .010 sec, in cm/sec2. (8f10.6)\n" % len(vals)
    v2 += fixed(vals, 8, 10, "%10.6f")
put("fuzz_motion", 5, v2.encode())

# GeoNet V2A, one channel: 16 text lines, 4 integer lines (10I8), 6 real lines (10F8)
n = len(vals)
text = ["Corrected accelerogram", "Site TEST", "Component N00E",
        "Number of points %d" % n, "data at 0.010 sec intervals",
        "Acceleration: peak   123.4 mm/s/s"] + ["text line %d" % k for k in range(10)]
ints = ["%8d" * 10 % tuple([0] * 10)] * 4
ints[3] = "%8d" * 10 % (0, 0, 0, n, n, n, 0, 0, 0, 0)
reals = ["%8.3f" * 10 % tuple([0.0] * 10)] * 6
v2a = "\n".join(text + ints + reals) + "\n" + fixed([1000 * v for v in vals], 10, 8, "%8.2f")
put("fuzz_motion", 5, v2a.encode())

# USGS SMC type 2: 11 text lines, 48 integers 8I10, 50 reals 5E15.7, comments, data 8E10
text = ["2 CORRECTED ACCELEROGRAM", "station", "event", "", "",
        "station component=  360", "", "", "", "", ""]
ih = [0] * 48
ih[15], ih[16] = 1, n
ints = ["".join("%10d" % x for x in ih[i:i + 8]) for i in range(0, 48, 8)]
rh = [0.0] * 50
rh[1] = 100.0
reals = ["".join("%15.7E" % x for x in rh[i:i + 5]) for i in range(0, 50, 5)]
smc = "\n".join(text + ints + reals + ["| a comment"]) + "\n" + fixed(vals, 8, 10, "%10.3E")
put("fuzz_motion", 6, smc.encode())

# CWA .acc: time (s) and acceleration (m/s^2), no header
acc = "".join("%8.3f %12.6f\n" % (0.01 * k, v) for k, v in enumerate(vals))
put("fuzz_motion", 7, acc.encode())

# fuzz_result: real cache entries and a shard manifest from a small run of the
# program (skipped when ./seislide is not built): 0 the entry file, 1 its
# payload alone, 2 the manifest, 3 K, N and the manifest's body.
import struct, subprocess, tempfile
if os.path.exists("./seislide"):
    mu = ",".join("%.2f" % (0.05 * k) for k in range(1, 17))  # 16 mu, as fuzz_result.c
    with tempfile.TemporaryDirectory() as t:
        os.makedirs(t + "/plant/A")
        os.makedirs(t + "/plant/B")
        shutil.copy("floors/01-ground.ini", t + "/plant/A/")
        shutil.copy("floors/04-roof36.ini", t + "/plant/B/")
        args = ["--sets", "5", "--mu", mu, "-q", "--created", "0"]
        subprocess.run(["./seislide", "run", t + "/plant", "--shard", "1/2", "-o", t + "/p1"] + args,
                       check=True)
        for p in sorted(glob.glob(t + "/p1/**/*.slr", recursive=True)):
            b = read(p)
            put("fuzz_result", 0, b)
            klen = struct.unpack("<Q", b[8:16])[0]
            put("fuzz_result", 1, b[16 + klen + 8:-4])
        m = read(t + "/p1/seislide-shard.bin")
        put("fuzz_result", 2, m)
        k, n = struct.unpack("<QQ", m[8:24])
        put("fuzz_result", 3, bytes([(k - 1) % 4, (n - 1) % 4]) + m[32:-4])
else:
    print("make-corpus.py: ./seislide not built: no fuzz_result seeds")
