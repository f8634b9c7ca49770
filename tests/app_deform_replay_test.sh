#!/usr/bin/env bash
# End to end (issue 5 point 6, issue 6 point 6): assets/logs/deform.jsonl (written by
# scripts/make-deform-log, which must reproduce it) sketches three sections, paints a stiff patch,
# and deforms the model twice: in "deform" mode (a handle stroke over the top, the view turned, a
# target stroke 0.3 above) and in "sculpt" mode (an open stroke on the model is recognised as a
# handle; the view turned, a target 0.2 above), and once more in "deform" mode with a shadow
# stroke on the projection plane (three strokes, deform_shadow 1). Its replay must refuse nothing but the
# out-of-range stiffness parameter, keep the model closed, manifold and free of self-intersections
# with the same connectivity, raise the vertices under each handle by about its target's height,
# leave the lower half bit-identical, and be bit-identical run to run.
set -euo pipefail
bin="${PLANESKETCH_BINARY:?}"
src="${PLANESKETCH_SOURCE_DIR:?}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

python3 "$src/scripts/make-deform-log" "$tmp/deform.jsonl"
cmp "$tmp/deform.jsonl" "$src/assets/logs/deform.jsonl" ||
  { echo "assets/logs/deform.jsonl is not what scripts/make-deform-log writes"; exit 1; }
python3 "$src/scripts/make-deform-log" --sketch-only "$tmp/sketch.jsonl"
"$bin" replay "$tmp/sketch.jsonl" -o "$tmp/sketch.obj" --report "$tmp/sketch.json" -q
"$bin" replay "$src/assets/logs/deform.jsonl" -o "$tmp/a.obj" --report "$tmp/a.json" -q 2>/dev/null
"$bin" replay "$src/assets/logs/deform.jsonl" -o "$tmp/b.obj" -q 2>/dev/null
cmp "$tmp/a.obj" "$tmp/b.obj" || { echo "deform replay is not bit-identical"; exit 1; }
python3 - "$tmp" <<'PY'
import json, sys
d = sys.argv[1]
r, s = json.load(open(f"{d}/a.json")), json.load(open(f"{d}/sketch.json"))
assert s["valid"] and s["refused"] == [], s
assert r["valid"], f"deformed model is not closed/manifold/outward/self-intersection free: {r}"
assert [m["message"] for m in r["refused"]] == ["stiffness must lie in [0, 1]; kept 1.000000"], r["refused"]
assert r["components"] == 1 and r["genus"] == 0, r
def read(p):
    lines = open(p).read().splitlines()
    return [l for l in lines if l.startswith("v ")], [l for l in lines if l.startswith("f ")]
(va, fa), (vb, fb) = read(f"{d}/sketch.obj"), read(f"{d}/a.obj")
assert fa == fb and len(va) == len(vb), "the deformation changed the connectivity"
a = [list(map(float, l.split()[1:4])) for l in va]
b = [list(map(float, l.split()[1:4])) for l in vb]
# The handles run over the top at y ~ 0.47 and y ~ -0.56 between x = -0.445 and 0.445; their
# targets are 0.3 and 0.2 higher.
rises = []
for y, lift in ((0.47, 0.3), (-0.56, 0.2)):
    under = [q[2] - p[2] for p, q in zip(a, b) if abs(p[1] - y) < 0.05 and abs(p[0]) < 0.3 and p[2] > 1.0]
    assert len(under) >= 10, (y, len(under))
    mean = sum(under) / len(under)
    assert min(under) > 0.65 * lift and abs(mean - lift) < 0.05, (y, min(under), mean)
    rises.append(f"{mean:.3f}")
# The third handle runs down the top at x ~ 0.55 (y from 0.17 to -0.17), its target 0.2 higher,
# its shadow bending the target towards +x by about 0.08 in the middle (y ~ 0), not at the ends.
def shift(sel):
    d = [[q[k] - p[k] for k in range(3)] for p, q in zip(a, b) if sel(p)]
    assert len(d) >= 2, len(d)
    return [sum(x[k] for x in d) / len(d) for k in range(3)]
mid = shift(lambda p: abs(p[1]) < 0.05 and abs(p[0] - 0.55) < 0.05 and p[2] > 1.0)
ends = shift(lambda p: abs(abs(p[1]) - 0.15) < 0.03 and abs(p[0] - 0.55) < 0.05 and p[2] > 1.0)
# (It lies in the first deformation's region too, which lifted it a little already.)
assert 0.15 < mid[2] < 0.3 and 0.15 < ends[2] < 0.3, (mid, ends)
assert mid[0] > 0.04 and mid[0] > ends[0] + 0.03, (mid, ends)
rises.append(f"{mid[2]:.3f} (bent {mid[0]:.3f} along x)")
moved = [i for i in range(len(va)) if va[i] != vb[i]]
assert 100 < len(moved) < len(va) // 2, len(moved)
low = [i for i in range(len(va)) if a[i][2] < 0.3]
assert len(low) > len(va) // 3 and all(va[i] == vb[i] for i in low), "the lower half moved"
print(f"deform replay ok: {len(moved)} of {len(va)} vertices moved, handle regions raised by {' and '.join(rises)}")
PY
