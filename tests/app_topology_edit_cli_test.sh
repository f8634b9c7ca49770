#!/usr/bin/env bash
# planesketch reconstruct --edits (thesis 6.4): two circles on z = 0 and z = 1, apart, give two
# components; a join stroke from one to the other gives one, valid; a split across two
# overlapping circles gives two. A bad edits file is refused with the edit index named, and
# writes no mesh.
set -euo pipefail
bin="${PLANESKETCH_BINARY:?}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

python3 - "$tmp" <<'PY'
import json, math, os, sys
d = sys.argv[1]
def circle(z, cx, r=0.5, n=40, phase=0.37):
    return [[cx + r * math.cos(2 * math.pi * i / n + phase), r * math.sin(2 * math.pi * i / n + phase), z] for i in range(n)]
def sections(dx):
    return {"format": "cross-sections", "version": 1,
            "planes": [{"normal": [0, 0, 1], "offset": 0.0}, {"normal": [0, 0, 1], "offset": 1.0}],
            "curves": [{"plane": 0, "points": circle(0.0, 0.0)}, {"plane": 1, "points": circle(1.0, dx, phase=0.91)}]}
json.dump(sections(2.0), open(os.path.join(d, "apart.json"), "w"))
json.dump(sections(0.5), open(os.path.join(d, "overlap.json"), "w"))
json.dump({"edits": [{"kind": "join", "stroke": [[0, 0, 0.2], [1, 0, 0.5], [2, 0, 0.8]]}]}, open(os.path.join(d, "join.json"), "w"))
json.dump({"edits": [{"kind": "split", "stroke": [[-1, 0, 0.5], [1.5, 0, 0.5]]}]}, open(os.path.join(d, "split.json"), "w"))
json.dump({"edits": [{"kind": "join", "stroke": [[0, 0, 0.2], [2, 0, 0.8]]}, {"kind": "merge", "stroke": []}]},
          open(os.path.join(d, "badkind.json"), "w"))
json.dump({"edits": [{"kind": "join", "stroke": [[0, 0, 0.2], [0.1, 0, 0.3]]}]}, open(os.path.join(d, "samepart.json"), "w"))
PY

components() { python3 -c 'import json,sys; r=json.load(open(sys.argv[1])); assert r["closed"] and r["manifold"] and r["outward"] and not r["self_intersecting"], r; assert r["max_curve_distance_relative"] < 1e-6, r; print(r["components"])' "$1"; }

"$bin" reconstruct "$tmp/apart.json" -o "$tmp/apart.obj" --report "$tmp/apart.rep" -q
[ "$(components "$tmp/apart.rep")" = 2 ] || { echo "two separate circles should give 2 components"; exit 1; }
"$bin" reconstruct "$tmp/apart.json" -o "$tmp/joined.obj" --report "$tmp/joined.rep" --edits "$tmp/join.json" -q
[ "$(components "$tmp/joined.rep")" = 1 ] || { echo "the join should give 1 component"; exit 1; }

"$bin" reconstruct "$tmp/overlap.json" -o "$tmp/overlap.obj" --report "$tmp/overlap.rep" -q --no-improve
[ "$(components "$tmp/overlap.rep")" = 1 ] || { echo "overlapping circles should give 1 component"; exit 1; }
"$bin" reconstruct "$tmp/overlap.json" -o "$tmp/split.obj" --report "$tmp/split.rep" --edits "$tmp/split.json" -q --no-improve
[ "$(components "$tmp/split.rep")" = 2 ] || { echo "the split should give 2 components"; exit 1; }

expect_refusal() {  # edits file, expected text
  if "$bin" reconstruct "$tmp/apart.json" -o "$tmp/refused.obj" --edits "$1" -q 2> "$tmp/err"; then
    echo "$1 was accepted"; exit 1
  fi
  grep -q "$2" "$tmp/err" || { echo "message for $1 lacks '$2':"; cat "$tmp/err"; exit 1; }
  [ ! -e "$tmp/refused.obj" ] || { echo "a mesh was written for $1"; exit 1; }
}
expect_refusal "$tmp/badkind.json" 'edits\[1\].kind'
expect_refusal "$tmp/samepart.json" 'same part'
expect_refusal "$tmp/missing.json" 'cannot read'
echo "topology edit CLI ok"
