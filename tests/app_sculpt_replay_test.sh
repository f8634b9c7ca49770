#!/usr/bin/env bash
# End to end (issue 6 points 7-8): scripts/make-sculpt-log writes the demo session followed by
# sculpting strokes: a cut across the top in "cut" mode (the cutting stroke, then a stroke on the
# side to remove) and a scratch-out in "sculpt" mode (recognised, then smoothed). Its replay must
# apply both (nothing refused), keep the model closed, manifold and free of self-intersections,
# remove everything above the cut, and be bit-identical run to run.
set -euo pipefail
bin="${PLANESKETCH_BINARY:?}"
src="${PLANESKETCH_SOURCE_DIR:?}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

python3 "$src/scripts/make-sculpt-log" "$tmp/sculpt.jsonl"
"$bin" replay "$src/assets/logs/demo.jsonl" -o "$tmp/demo.obj" -q
"$bin" replay "$tmp/sculpt.jsonl" -o "$tmp/a.obj" --report "$tmp/a.json" -q
"$bin" replay "$tmp/sculpt.jsonl" -o "$tmp/b.obj" -q
cmp "$tmp/a.obj" "$tmp/b.obj" || { echo "sculpt replay is not bit-identical"; exit 1; }
python3 - "$tmp" <<'PY'
import json, sys
d = sys.argv[1]
r = json.load(open(f"{d}/a.json"))
assert r["valid"], f"sculpted model is not closed/manifold/outward/self-intersection free: {r}"
assert r["refused"] == [], f"a sculpting stroke was refused: {r['refused']}"
assert r["components"] == 1, r
def verts(p):
    return [list(map(float, l.split()[1:4])) for l in open(p) if l.startswith("v ")]
demo, cut = verts(f"{d}/demo.obj"), verts(f"{d}/a.obj")
# The cutting stroke is the window row y = 235 of an 800-pixel view from (8, 0, 0) looking down
# -x with fov 40 deg: the swept surface is z = k (8 - x), k = (1 - 235/400) tan(20 deg).
k = (1 - 235 / 400) * 0.36397023426620234
assert max(v[2] for v in demo) > 1.9
worst = max(v[2] - k * (8 - v[0]) for v in cut)
assert worst < 1e-6, f"material left above the cut: {worst}"
assert max(v[2] for v in cut) < 1.3
print("sculpt replay ok:", r["faces"], "faces, genus", r["genus"])
PY
