#!/usr/bin/env bash
# The extrusion's reference plane in the window (docs/sculpting.md, "In the window"), under
# xvfb-run on lavapipe (skipped without xvfb-run): a log that sketches, enters "extrude" mode
# and draws the base loop (scripts/make-sculpt-ops-log, cut before the view turns to face the
# plane), then looks from an oblique view. The screenshot differs from the one without the base
# loop (the plane and the base curve are drawn while the silhouette is awaited), and differs
# again after extrude_tilt 0.5 (the plane turns with the parameter the panel's slider sets);
# nothing is refused.
source "$(dirname "${BASH_SOURCE[0]}")/xvfb_window.sh"

python3 "$src/scripts/make-deform-log" --sketch-only "$tmp/sketch.jsonl"
"$bin" replay "$tmp/sketch.jsonl" -o "$tmp/sketch.obj" -q 2>/dev/null
python3 "$src/scripts/make-sculpt-ops-log" --model "$tmp/sketch.obj" "$tmp/extrude.jsonl" extrude >/dev/null
python3 - "$tmp" <<'PY'
import json, sys
d = sys.argv[1]
lines = [l for l in open(f"{d}/extrude.jsonl").read().splitlines() if l.strip()]
events = [json.loads(l) for l in lines]
start = next(i for i, e in enumerate(events) if e.get("type") == "tool_mode" and e.get("mode") == "extrude")
turn = next(i for i in range(start, len(events)) if events[i].get("type") == "camera")
t = events[turn]["t"]
oblique = dict(events[turn]["camera"], eye=[5.0, -4.0, 3.0], target=[0.5, 0.0, 0.0], up=[0.0, 0.0, 1.0])
def write(name, body, extra=()):
    out = body + [json.dumps({"t": t, "type": "camera", "camera": oblique})] + list(extra)
    open(f"{d}/{name}.jsonl", "w").write("\n".join(out) + "\n")
write("no_base", lines[:start + 1])
write("base", lines[:turn])
write("tilted", lines[:turn], [json.dumps({"t": t, "type": "parameter", "name": "extrude_tilt", "value": 0.5})])
PY
for n in no_base base tilted; do
  win --replay "$tmp/$n.jsonl" --screenshot "$tmp/$n.png" 2>"$tmp/$n.err" || { cat "$tmp/$n.err"; fail "window on $n"; }
  [ -s "$tmp/$n.png" ] || fail "no screenshot of $n"
  if grep -q "refused" "$tmp/$n.err"; then cat "$tmp/$n.err"; fail "$n: something was refused"; fi
done
cmp -s "$tmp/no_base.png" "$tmp/base.png" && fail "the pending extrusion's plane is not shown"
cmp -s "$tmp/base.png" "$tmp/tilted.png" && fail "the plane does not turn with extrude_tilt"
echo "window extrusion plane ok"
