#!/usr/bin/env bash
# End to end (issue 6): one stroke log per sculpting operation, written by
# scripts/make-sculpt-ops-log on the capped stack of scripts/make-deform-log --sketch-only and
# replayed headless. Each result must be closed, manifold, outward and free of
# self-intersections, with the expected change:
#   tunnel           genus + 1, one component, no material left inside the drawn circle, volume down;
#   extrude          genus and components unchanged, volume up by about the half ellipsoid drawn,
#                    the new material near the stroke on the outer side, the silhouette's tip on it;
#   dig-tunnel       a U-shaped silhouette drawn into the model and out at its back, bent towards
#                    +y: genus + 1, hollow along the bent skeleton, solid on the straight line from
#                    the base where the skeleton has moved aside;
#   extrude-rotated  the same as extrude on the plane turned by extrude_spin / extrude_tilt: the tip where the
#                    turned plane puts it (far from the unturned tip), kept by a saved session;
#   miss             a refused extrude_tilt beyond 90 degrees and four refused strokes (off the
#                    model in sculpt, tunnel and extrude modes, a degenerate silhouette), each with
#                    its message, the model bit-identical (the degenerate silhouette is drawn on
#                    the unturned plane: the refused tilt was not kept);
#   undo / redo      undoing a tunnel or an extrusion gives the sketch back bit for bit, redoing
#                    the tunnel gives the tunnel's model bit for bit.
# Replays are bit-identical run to run.
set -euo pipefail
bin="${PLANESKETCH_BINARY:?}"
src="${PLANESKETCH_SOURCE_DIR:?}"
tmp="$(mktemp -d)"
trap 'rc=$?; if [ $rc -eq 0 ]; then rm -rf "$tmp"; else echo "files kept in $tmp"; fi' EXIT
gen="$src/scripts/make-sculpt-ops-log"
# Every replay's messages go to a log that is shown when the replay fails (a quiet replay that
# failed once under load left nothing to read).
replay() {  # LOGNAME ARGS...
  local log="$tmp/$1.err"; shift
  "$bin" replay "$@" -q 2>"$log" || { rc=$?; echo "replay $* failed (exit $rc):"; cat "$log"; exit 1; }
}

python3 "$src/scripts/make-deform-log" --sketch-only "$tmp/sketch.jsonl"
replay sketch "$tmp/sketch.jsonl" -o "$tmp/sketch.obj"
run() {  # NAME STEP...: generate, replay (model, report, expectations)
  local name="$1"; shift
  python3 "$gen" --model "$tmp/sketch.obj" "$tmp/$name.jsonl" "$@" > "$tmp/$name.expect.json"
  replay "$name" "$tmp/$name.jsonl" -o "$tmp/$name.obj" --report "$tmp/$name.json"
}
run tunnel tunnel
run extrude extrude
run rotated extrude-rotated
run dig dig-tunnel
run miss miss
run tunnel_undo tunnel undo
run tunnel_redo tunnel undo redo
run extrude_undo extrude-rotated undo

replay rotated2 "$tmp/rotated.jsonl" -o "$tmp/rotated2.obj" --save-session "$tmp/rotated.session.json"
cmp "$tmp/rotated.obj" "$tmp/rotated2.obj" || { echo "extrusion replay is not bit-identical"; exit 1; }
replay tunnel2 "$tmp/tunnel.jsonl" -o "$tmp/tunnel2.obj"
cmp "$tmp/tunnel.obj" "$tmp/tunnel2.obj" || { echo "tunnel replay is not bit-identical"; exit 1; }
# The saved session keeps the plane's rotation: loading it rebuilds the same model.
head -n 1 "$tmp/rotated.jsonl" > "$tmp/header.jsonl"
replay rotated3 "$tmp/header.jsonl" --session "$tmp/rotated.session.json" -o "$tmp/rotated3.obj"
cmp "$tmp/rotated.obj" "$tmp/rotated3.obj" || { echo "the saved session does not rebuild the turned extrusion"; exit 1; }
cmp "$tmp/miss.obj" "$tmp/sketch.obj" || { echo "refused strokes changed the model"; exit 1; }
cmp "$tmp/tunnel_undo.obj" "$tmp/sketch.obj" || { echo "undo of a tunnel does not restore the model"; exit 1; }
cmp "$tmp/extrude_undo.obj" "$tmp/sketch.obj" || { echo "undo of an extrusion does not restore the model"; exit 1; }
cmp "$tmp/tunnel_redo.obj" "$tmp/tunnel.obj" || { echo "redo of a tunnel does not give the tunnel back"; exit 1; }

python3 - "$tmp" "$src/scripts" <<'PY'
import json, math, sys
d = sys.argv[1]
sys.path.insert(0, sys.argv[2])
from sculptlog import add, cam, cross, dot, norm, project, read_obj, scale, signed_volume, sub

def winding(vs, fs, p):
    """Generalised winding number: about 1 inside a closed mesh, 0 outside."""
    total = 0.0
    for f in fs:
        a, b, c = (sub(vs[k], p) for k in f)
        la, lb, lc = norm(a), norm(b), norm(c)
        total += 2 * math.atan2(dot(a, cross(b, c)), la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb)
    return total / (4 * math.pi)

def load(name):
    r = json.load(open(f"{d}/{name}.json"))
    vs, fs = read_obj(f"{d}/{name}.obj")
    return r, vs, fs, json.load(open(f"{d}/{name}.expect.json"))

sv, sf = read_obj(f"{d}/sketch.obj")
v0 = signed_volume(sv, sf)
sketch = set(map(tuple, sv))
report = []
for name in ("tunnel", "extrude", "rotated", "dig", "tunnel_undo", "tunnel_redo", "extrude_undo"):
    r = load(name)[0]
    assert r["valid"], f"{name}: not closed/manifold/outward/self-intersection free: {r}"
    assert r["refused"] == [], f"{name}: refused {r['refused']}"
    assert r["components"] == 1, (name, r["components"])

# Tunnel: genus 0 -> 1, nothing inside the drawn circle (radius 50 px about (640, 400); its
# 48-gon's inscribed radius is 49.89 px) seen from the stroke's camera.
r, vs, fs, _ = load("tunnel")
assert r["genus"] == 1, r["genus"]
front = cam((8.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0))
inner = min(math.hypot(p[0] - 640.0, p[1] - 400.0) for p in (project(front, v) for v in vs))
assert inner > 49.5, f"material left inside the tunnel: a vertex {inner:.2f} px from its axis"
dv = signed_volume(vs, fs) - v0
assert dv < -0.4, dv  # a bore of radius ~0.32 through the ~2-wide body: ~0.6-0.8
report.append(f"tunnel: genus 1, volume {dv:+.3f}")

# Extrusions: genus 0, the silhouette's tip on the result, new material only near the stroke on
# the outer side, about the half ellipsoid's volume added.
tips = {}
for name, step in (("extrude", "extrude"), ("rotated", "extrude-rotated")):
    r, vs, fs, e = load(name)
    e = e[step]
    assert r["genus"] == 0, (name, r["genus"])
    c, n = e["centre"], e["region_normal"]
    tip_gap = min(norm(sub(v, e["tip"])) for v in vs)
    assert tip_gap < 0.01, f"{name}: no vertex at the silhouette's tip ({tip_gap:.4f} away)"
    new = [v for v in vs if tuple(v) not in sketch]
    assert len(new) > 500, (name, len(new))
    far = max(norm(sub(v, c)) for v in new)
    low = min(dot(sub(v, c), n) for v in new)
    assert far < e["height"] + 0.1 and low > -0.1, f"{name}: new material away from the stroke ({far:.3f}, {low:.3f})"
    dv = signed_volume(vs, fs) - v0
    half_ellipsoid = 2.0 / 3.0 * math.pi * (0.95 * e["half_width"]) ** 2 * e["height"]
    assert 0.6 * half_ellipsoid < dv < 1.1 * half_ellipsoid, (name, dv, half_ellipsoid)
    tips[name] = e["tip"]
    report.append(f"{name}: volume {dv:+.4f} (half ellipsoid {half_ellipsoid:.4f}), tip within {tip_gap:.4f}")
# The turned plane moves the part: its tip is far from the unturned one, and below it (tilt 0.5
# about a diameter along +y turns the normal axis +x towards -z).
moved = norm(sub(tips["rotated"], tips["extrude"]))
assert moved > 0.25 and tips["rotated"][2] < tips["extrude"][2] - 0.05, (tips, moved)
s = json.load(open(f"{d}/rotated.session.json"))
assert [(o["kind"], o["spin"], o["tilt"]) for o in s["ops"]] == [("extrude", 0.6, 0.5)], s["ops"]

# Bent tunnel: genus 0 -> 1; the points of the bent skeleton (u = mid + 0.8 f^2 at the fraction f
# of the 2.5 depth) inside the sketch are hollow in the result; the straight line from the base
# centre at f = 0.6 (0.29 from the skeleton; the tunnel's radius is about 0.23) is still solid.
r, vs, fs, e = load("dig")
e = e["dig-tunnel"]
assert r["genus"] == 1, r["genus"]
c, n, a = e["centre"], e["normal_axis"], e["across"]
for f in (0.2, 0.4, 0.6):
    bent = add(c, add(scale(e["mid"] + 0.8 * f * f, a), scale(-2.5 * f, n)))
    assert winding(sv, sf, bent) > 0.95, (f, bent)
    assert winding(vs, fs, bent) < 0.05, f"material left on the bent tunnel's skeleton at {f}: {bent}"
straight = add(c, add(scale(e["mid"], a), scale(-1.5, n)))
assert winding(vs, fs, straight) > 0.95, f"the tunnel is straight: {straight} is hollow"
dv = signed_volume(vs, fs) - v0
assert dv < -0.2, dv
report.append(f"bent tunnel: genus 1, volume {dv:+.3f}")

# Refusals: each named, the model untouched (compared bit for bit above).
r = load("miss")[0]
words = ["tilt must lie strictly between -90 and 90 degrees (found 115 degrees)", "the stroke misses the model", "tunnel: the tunnel stroke leaves the model",
         "extrude: the base stroke misses the model", "extrude: the silhouette stroke is degenerate"]
got = [m["message"] for m in r["refused"]]
assert len(got) == len(words) and all(w in m for w, m in zip(words, got)), got
print("sculpt ops replay ok:", "; ".join(report))
PY
