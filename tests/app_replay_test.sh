#!/usr/bin/env bash
# End to end: replaying the bundled demo logs builds a valid closed model and a PNG, and
# replaying one log twice gives bit-identical output. Bad logs fail with a clear message.
set -euo pipefail
bin="${PLANESKETCH_BINARY:?}"
src="${PLANESKETCH_SOURCE_DIR:?}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

for log in demo figure; do
  "$bin" replay "$src/assets/logs/$log.jsonl" -o "$tmp/$log-1.off" --png "$tmp/$log.png" --size 320x200 \
    --report "$tmp/$log.json" -q --no-improve
  "$bin" replay "$src/assets/logs/$log.jsonl" -o "$tmp/$log-2.off" -q --no-improve
  cmp "$tmp/$log-1.off" "$tmp/$log-2.off" || { echo "replay of $log is not bit-identical"; exit 1; }
  [ -s "$tmp/$log.png" ] || { echo "no PNG for $log"; exit 1; }
  python3 - "$tmp/$log.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert r["valid"], f"replayed model is not closed/manifold/outward/self-intersection free: {r}"
assert r["sections"] >= 3, r
assert r["faces"] > 100, r
print(sys.argv[1], "sections", r["sections"], "faces", r["faces"], "components", r["components"], "genus", r["genus"])
PY
done

# The vase has a ring section (rule 2): a hole through it gives genus >= 1 or a cavity.
# Bad input: a malformed log names file and line, exits non-zero, writes nothing.
printf '{"format":"planesketch-stroke-log","version":1}\n{"t":1,"type":"pen"\n' > "$tmp/bad.jsonl"
if "$bin" replay "$tmp/bad.jsonl" -o "$tmp/bad.off" 2> "$tmp/err"; then echo "bad log accepted"; exit 1; fi
grep -q "bad.jsonl:" "$tmp/err" || { echo "message does not name the file:"; cat "$tmp/err"; exit 1; }
[ ! -e "$tmp/bad.off" ] || { echo "output written for a bad log"; exit 1; }
if "$bin" replay "$tmp/missing.jsonl" 2> "$tmp/err"; then echo "missing log accepted"; exit 1; fi
if "$bin" replay "$tmp" 2> "$tmp/err"; then echo "directory accepted as a log"; exit 1; fi
if "$bin" replay "$src/assets/logs/demo.jsonl" --size 0x0 2> "$tmp/err"; then echo "bad size accepted"; exit 1; fi
grep -q -- "--size" "$tmp/err"
echo "replay ok"
