#!/usr/bin/env bash
# Journaled file opens (issue 7 point 7; docs/stroke-log.md, event `open`): a session started from
# a saved session file (`replay --session S --journal J`, the headless counterpart of the
# window's --session / Ctrl+O) journals the open first, with the file's absolute path and
# digest. Recovering J opens the same file again and rebuilds the model byte for byte; a file
# that changed since, or is gone, is refused with one message naming it (and the journal is only
# read). Likewise for a mesh imported as the base (`--base`).
set -euo pipefail
bin="${PLANESKETCH_BINARY:?}"
src="${PLANESKETCH_SOURCE_DIR:?}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

# The deformation log is the sketch-only log followed by the deformation: its second part,
# replayed on top of the sketch's saved session, deforms the loaded model.
python3 "$src/scripts/make-deform-log" --sketch-only "$tmp/sketch.jsonl"
n=$(($(wc -l <"$tmp/sketch.jsonl") - 1))  # header and events; its last line is the end marker
cmp -s <(sed -n "2,${n}p" "$src/assets/logs/deform.jsonl") <(sed -n "2,${n}p" "$tmp/sketch.jsonl") ||
  fail "assets/logs/deform.jsonl does not begin with the sketch-only log's events"
{ head -n 1 "$src/assets/logs/deform.jsonl"; tail -n +"$((n + 1))" "$src/assets/logs/deform.jsonl"; } >"$tmp/deform_only.jsonl"
"$bin" replay "$tmp/sketch.jsonl" --save-session "$tmp/s.json" -o "$tmp/sketch.obj" -q 2>/dev/null

"$bin" replay "$tmp/deform_only.jsonl" --session "$tmp/s.json" --journal "$tmp/j.jsonl" -o "$tmp/ref.obj" -q 2>/dev/null
cmp -s "$tmp/sketch.obj" "$tmp/ref.obj" && fail "the deformation did not change the loaded model"
python3 - "$tmp" <<'PY'
import json, sys
d = sys.argv[1]
lines = open(f"{d}/j.jsonl").read().splitlines()
first = json.loads(lines[1])
assert first["type"] == "open" and first["kind"] == "session", first
assert first["path"] == f"{d}/s.json", first
assert len(first["digest"]) == 16 and first["t"] == 0, first
assert sum('"type":"open"' in l for l in lines) == 1, "one open event"
PY
"$bin" recover "$tmp/j.jsonl" -o "$tmp/rec.obj" 2>"$tmp/err" || { cat "$tmp/err"; fail "recover failed"; }
cmp "$tmp/ref.obj" "$tmp/rec.obj" || fail "the recovered model differs from the journaled session's"
grep -q "not loaded" "$tmp/err" && { cat "$tmp/err"; fail "a refusal while recovering an unchanged file"; }

# The file changed since: the open is refused, naming it; nothing then builds a model.
cp "$tmp/s.json" "$tmp/s.saved"
printf ' ' >>"$tmp/s.json"
if "$bin" recover "$tmp/j.jsonl" -o "$tmp/changed.obj" 2>"$tmp/err"; then fail "recovered from a changed file"; fi
grep -q "session not loaded: $tmp/s.json: the file changed since the session opened it" "$tmp/err" ||
  { cat "$tmp/err"; fail "no message for the changed file"; }
[ -e "$tmp/changed.obj" ] && fail "an output file from a refused open"
rm "$tmp/s.json"
if "$bin" recover "$tmp/j.jsonl" -o "$tmp/gone.obj" 2>"$tmp/err"; then fail "recovered from a missing file"; fi
grep -q "session not loaded: $tmp/s.json: cannot be read" "$tmp/err" || { cat "$tmp/err"; fail "no message for the missing file"; }

# An imported base mesh: the same, as an `open` of kind "mesh".
head -n 1 "$tmp/sketch.jsonl" >"$tmp/header.jsonl"
"$bin" replay "$tmp/header.jsonl" --base "$tmp/sketch.obj" --journal "$tmp/jm.jsonl" -o "$tmp/base_ref.obj" -q 2>/dev/null
grep -q '"kind":"mesh"' "$tmp/jm.jsonl" || fail "no open event for the base mesh"
"$bin" recover "$tmp/jm.jsonl" -o "$tmp/base_rec.obj" 2>/dev/null || fail "recover of the base mesh failed"
cmp "$tmp/base_ref.obj" "$tmp/base_rec.obj" || fail "the recovered base differs"
echo "journaled opens ok"
