#!/usr/bin/env bash
# The window's session files (docs/session-format.md), under xvfb-run on lavapipe (skipped without
# xvfb-run): `--session S.json` is loaded through the preview worker before the replayed events,
# so the screenshot shows the saved model (it differs from the empty session's), and a bad
# session file is reported as one message naming the JSON problem while the window goes on.
source "${PLANESKETCH_SOURCE_DIR:?}/tests/xvfb_window.sh"

python3 "$src/scripts/make-deform-log" --sketch-only "$tmp/sketch.jsonl"
"$bin" replay "$tmp/sketch.jsonl" --save-session "$tmp/s.json" -q 2>/dev/null
head -1 "$tmp/sketch.jsonl" >"$tmp/header.jsonl"  # no events: the view of the log's start
win --replay "$tmp/header.jsonl" --screenshot "$tmp/empty.png" 2>/dev/null
win --replay "$tmp/header.jsonl" --screenshot "$tmp/loaded.png" --session "$tmp/s.json" 2>"$tmp/err" ||
  { cat "$tmp/err"; fail "window with --session failed"; }
[ -s "$tmp/loaded.png" ] || fail "no screenshot"
cmp -s "$tmp/empty.png" "$tmp/loaded.png" && fail "the loaded session is not shown"
printf '{"format":"planesketch-session","version":7}\n' >"$tmp/bad.json"
win --replay "$tmp/header.jsonl" --screenshot "$tmp/bad.png" --session "$tmp/bad.json" 2>"$tmp/err" ||
  { cat "$tmp/err"; fail "a bad session file stopped the window"; }
grep -q "session not loaded: $tmp/bad.json: version: unsupported session version 7" "$tmp/err" ||
  { cat "$tmp/err"; fail "no message for the bad session file"; }
cmp -s "$tmp/empty.png" "$tmp/bad.png" || fail "a refused session changed the view"
echo "window session files ok"
