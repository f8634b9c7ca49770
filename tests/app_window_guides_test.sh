#!/usr/bin/env bash
# The window's sketching guides (docs/session.md, issue 7 point 4), under xvfb-run on lavapipe
# (skipped without xvfb-run): a 5-section vase session (horizontal sections at z = -0.6, 0, 0.6,
# profiles on x = 0 and y = 0) loaded into the window with the z plane moved to 0.3, where no
# section lies: the screenshot shows the open rule-4 crossing markers (each profile, the vase
# wall in section, crosses z = 0.3 four times) in their colour; in sculpt mode, which has no
# guides, none.
source "${PLANESKETCH_SOURCE_DIR:?}/tests/xvfb_window.sh"

"$bin" synth-log --preset vase --sections 5 -o "$tmp/vase.jsonl"
"$bin" replay "$tmp/vase.jsonl" --save-session "$tmp/s.json" -q 2>/dev/null
python3 - "$tmp" <<'PY'
import json, sys
d = sys.argv[1]
header = json.loads(open(f"{d}/vase.jsonl").readline())
for p in header["planes"]:
    if p["normal"] == [0.0, 0.0, 1.0]:
        p["offset"] = 0.3
open(f"{d}/z03.jsonl", "w").write(json.dumps(header) + "\n")
open(f"{d}/sculpt.jsonl", "w").write(json.dumps(header) + "\n" + '{"t":0,"type":"tool_mode","mode":"sculpt"}\n')
PY
win --replay "$tmp/z03.jsonl" --session "$tmp/s.json" --screenshot "$tmp/sketch.png" 2>"$tmp/err" || { cat "$tmp/err"; fail "window failed"; }
win --replay "$tmp/sculpt.jsonl" --session "$tmp/s.json" --screenshot "$tmp/sculpt.png" 2>"$tmp/err" || { cat "$tmp/err"; fail "window failed"; }

# Pixels of the open-crossing marker colour (0.85, 0.10, 0.75) within 12 levels per channel.
python3 - "$tmp" <<'PY'
import struct, sys, zlib
def rgba_rows(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    pos, idat = 8, b""
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and ctype in (2, 6), (depth, ctype)
            bpp = 4 if ctype == 6 else 3
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, stride, prev, rows = zlib.decompress(idat), w * bpp, bytearray(w * bpp), []
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append((line, bpp))
        prev = line
    return rows
def markers(path):
    want = (round(0.85 * 255), round(0.10 * 255), round(0.75 * 255))
    count = 0
    for line, bpp in rgba_rows(path):
        for i in range(0, len(line), bpp):
            count += all(abs(line[i + k] - want[k]) <= 12 for k in range(3))
    return count
d = sys.argv[1]
sketch, sculpt = markers(f"{d}/sketch.png"), markers(f"{d}/sculpt.png")
assert sketch >= 8 * 40, f"the crossing markers are missing from the window's picture: {sketch} marker pixels"
assert sculpt == 0, f"marker pixels in sculpt mode: {sculpt}"
print(f"marker pixels: sketch mode {sketch}, sculpt mode {sculpt}")
PY
echo "window guides ok"
