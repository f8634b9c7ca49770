#!/usr/bin/env bash
# Journal under kill -9 (issue 8.5, issue 7.8): a journaling headless replay of the demo log is
# killed with SIGKILL at seeded pseudo-random points; each time the session is recovered from
# its journal and the recovered mesh must equal, byte for byte, the mesh built by replaying the
# same prefix of the log (the events the journal holds). Every other run the journal's last
# line is additionally torn (cut mid-line, as a crash inside write(2) would leave it).
# Also: a clean run leaves a finished journal that recovery skips, automatic discovery of the
# newest unfinished journal, the `--recover` spelling, and bad journals.
#
# Knobs (environment): PLANESKETCH_KILL_SEED (default 20261122), PLANESKETCH_KILL_RUNS (20),
# PLANESKETCH_KILL_PACE_MS (0.5). About 40 s on 2 idle cores.
set -euo pipefail
bin="${PLANESKETCH_BINARY:?}"
src="${PLANESKETCH_SOURCE_DIR:?}"
tmp="$(mktemp -d)"
child=""
cleanup() {
  if [ -n "$child" ]; then kill -9 "$child" 2>/dev/null || true; fi
  rm -rf "$tmp"
}
trap cleanup EXIT
export XDG_STATE_HOME="$tmp/state"  # never look at the user's own journals
log="$src/assets/logs/demo.jsonl"
seed="${PLANESKETCH_KILL_SEED:-20261122}"
runs="${PLANESKETCH_KILL_RUNS:-20}"
pace="${PLANESKETCH_KILL_PACE_MS:-0.5}"
nevents=$(( $(wc -l < "$log") - 1 ))
start=$SECONDS
fail() { echo "FAIL: $*"; exit 1; }

# === A clean journaled run: the journal is the log plus the end marker, the model is unchanged.
"$bin" replay "$log" -q --no-improve -o "$tmp/full.off"
"$bin" replay "$log" -q --no-improve -o "$tmp/full-j.off" --journal "$tmp/full.jsonl"
cmp -s "$tmp/full.off" "$tmp/full-j.off" || fail "journaling changed the replayed model"
head -n $((nevents + 1)) "$tmp/full.jsonl" | cmp -s - "$log" || fail "the journal of a clean run is not the log"
tail -n 1 "$tmp/full.jsonl" | grep -q '"type":"end"' || fail "a clean run's journal has no end marker"
[ "$(wc -l < "$tmp/full.jsonl")" -eq $((nevents + 2)) ] || fail "clean journal has extra lines"
if "$bin" replay "$log" -q --journal "$tmp/full.jsonl" 2> "$tmp/err"; then fail "an existing journal was overwritten"; fi
grep -q "full.jsonl: exists" "$tmp/err" || fail "unclear message for an existing journal: $(cat "$tmp/err")"

# === Kill, recover, compare.
RANDOM=$seed
equal=0 empty=0 torn=0 midstroke=0 rebuild=0
mapfile -t ups < <(grep -n '"phase":"up"' "$log" | cut -d: -f1 | awk '{ print $1 - 1 }')  # event indices (1-based)
points=()
for ((i = 0; i < runs; ++i)); do
  # Stratified: run i kills at a seeded random point of the i-th of `runs` equal slices of the
  # session, so the points cover it from the first events to the last stroke. Kill once the
  # journal holds >= target events.
  lo=$(( i * nevents / runs + 1 )) hi=$(( (i + 1) * nevents / runs ))
  target=$(( lo + (RANDOM * 32768 + RANDOM) % (hi - lo + 1) ))
  if (( i % 4 == 2 )); then
    # Snap to the next pen-up in the log: the kill then lands while that stroke's model is being
    # rebuilt (the up is journaled before it is applied; the journal grows no further until then).
    for u in "${ups[@]}"; do (( u >= target )) && { target=$u; break; }; done
  fi
  j="$tmp/kill-$i.jsonl"
  "$bin" replay "$log" -q --no-improve --pace-ms "$pace" --journal "$j" > /dev/null 2>&1 &
  child=$!
  while :; do
    lines=0
    [ -f "$j" ] && lines=$(wc -l < "$j")
    [ "$lines" -ge $((target + 1)) ] && break
    kill -0 "$child" 2>/dev/null || break
    sleep 0.005
  done
  kill -9 "$child" 2>/dev/null || fail "run $i: the replay ended before the kill point ($target of $nevents events)"
  wait "$child" 2>/dev/null && fail "run $i: replay survived SIGKILL"
  child=""
  tail -n 1 "$j" | grep -q '"type":"end"' && fail "run $i: a killed session's journal has the end marker"
  tail -n 1 "$j" | grep -q '"phase":"up"' && rebuild=$((rebuild + 1))  # killed while rebuilding the model
  if (( i % 2 == 1 )); then
    # Tear the last line: keep at least its first byte, lose at least "}\n".
    last_len=$(tail -n 1 "$j" | wc -c)
    cut=$(( RANDOM % (last_len - 2) + 2 ))
    truncate -s -"$cut" "$j"
    torn=$((torn + 1))
  fi
  held=$(( $(wc -l < "$j") - 1 ))  # complete event lines (a torn last line has no newline)
  [ "$held" -ge 0 ] || fail "run $i: journal lost its header"
  points+=("$target:$held")
  head -n $((held + 1)) "$log" > "$tmp/prefix.jsonl"
  head -n $((held + 1)) "$j" | cmp -s - "$tmp/prefix.jsonl" || fail "run $i: the journal is not a prefix of the log"
  # Killed inside a stroke (down journaled, its up not yet): recovery cuts the stroke off.
  if awk '/"phase":"down"/ { d = NR } /"phase":"up"/ { u = NR } END { exit !(d > u) }' "$tmp/prefix.jsonl"; then
    midstroke=$((midstroke + 1))
  fi
  rm -f "$tmp/rec.off" "$tmp/exp.off"
  set +e
  "$bin" recover "$j" -q --no-improve -o "$tmp/rec.off" --report "$tmp/rec.json" 2> "$tmp/rec.err" &
  rp=$!
  "$bin" replay "$tmp/prefix.jsonl" -q --no-improve -o "$tmp/exp.off" 2> "$tmp/exp.err"
  exp_rc=$?
  wait "$rp"
  rec_rc=$?
  set -e
  if (( i % 2 == 1 )); then
    grep -q "truncated last line dropped" "$tmp/rec.err" || fail "run $i: torn line not reported: $(cat "$tmp/rec.err")"
  fi
  if [ "$exp_rc" -ne 0 ]; then
    # The prefix built no model yet (killed before the first accepted stroke): recovery must
    # say the same and write nothing.
    grep -q "built no model" "$tmp/exp.err" || fail "run $i: prefix replay failed: $(cat "$tmp/exp.err")"
    [ "$rec_rc" -ne 0 ] || fail "run $i: recovery built a model the prefix does not"
    grep -q "built no model" "$tmp/rec.err" || fail "run $i: recovery failed differently: $(cat "$tmp/rec.err")"
    [ ! -e "$tmp/rec.off" ] || fail "run $i: partial output"
    empty=$((empty + 1))
  else
    [ "$rec_rc" -eq 0 ] || fail "run $i: recovery failed: $(cat "$tmp/rec.err")"
    cmp -s "$tmp/rec.off" "$tmp/exp.off" || fail "run $i: recovered model differs from the prefix's ($held events)"
    python3 - "$tmp/rec.json" "$held" "$((i % 2))" <<'PY' || fail "run $i: report"
import json, sys
r = json.load(open(sys.argv[1]))
assert r["events"] == int(sys.argv[2]), r["events"]
assert r["finished"] is False and r["torn_last_line_dropped"] == (sys.argv[3] == "1"), r
PY
    equal=$((equal + 1))
  fi
  rm -f "$j"
done
echo "kill points (target:events held, of $nevents): ${points[*]}"
echo "runs $runs: $equal equal meshes, $empty before the first model, $torn torn last lines, $midstroke mid-stroke, $rebuild during a rebuild; seed $seed, pace $pace ms"
[ $((equal + empty)) -eq "$runs" ] || fail "not every run checked"
[ "$equal" -ge $((runs / 2)) ] || fail "too few kills after the first model ($equal of $runs)"

# === Discovery: the newest unfinished, unlocked journal in the journal directory.
d="$XDG_STATE_HOME/planesketch"
mkdir -p "$d"
cp "$tmp/full.jsonl" "$d/journal-1-1.jsonl"  # finished: skipped
if "$bin" recover -q -o "$tmp/none.off" 2> "$tmp/err"; then fail "a finished journal was recovered"; else rc=$?; fi
[ "$rc" -eq 3 ] || fail "nothing to recover should exit 3, got $rc"
grep -q "no unfinished journal in $d" "$tmp/err" || fail "unclear message: $(cat "$tmp/err")"
[ ! -e "$tmp/none.off" ] || fail "output without a journal"
head -n 2000 "$log" > "$d/journal-2-2.jsonl"
head -n 1200 "$log" > "$tmp/old.jsonl" && cp "$tmp/old.jsonl" "$d/journal-0-0.jsonl" && touch -d '1 hour ago' "$d/journal-0-0.jsonl"
head -n 2000 "$log" > "$tmp/p2000.jsonl"
"$bin" replay "$tmp/p2000.jsonl" -q --no-improve -o "$tmp/p2000.off"
"$bin" --recover -q --no-improve -o "$tmp/auto.off" 2> "$tmp/err" || fail "--recover: $(cat "$tmp/err")"
grep -q "recovering $d/journal-2-2.jsonl" "$tmp/err" || fail "--recover picked another journal: $(cat "$tmp/err")"
cmp -s "$tmp/auto.off" "$tmp/p2000.off" || fail "--recover model differs"
"$bin" recover --list > "$tmp/list" || fail "--list"
grep -q "^finished .*journal-1-1.jsonl" "$tmp/list" && grep -q "^unfinished .*journal-2-2.jsonl" "$tmp/list" ||
  fail "--list: $(cat "$tmp/list")"
# A journal locked by a live session is not offered.
"$bin" replay "$log" -q --no-improve --pace-ms 5 --journal "$d/journal-9-9.jsonl" > /dev/null 2>&1 &
child=$!
while [ ! -s "$d/journal-9-9.jsonl" ]; do sleep 0.01; done
"$bin" recover --list > "$tmp/list"
grep -q "^in use .*journal-9-9.jsonl" "$tmp/list" || fail "live journal not shown in use: $(cat "$tmp/list")"
"$bin" recover -q --no-improve -o "$tmp/auto2.off" 2> "$tmp/err" || fail "recover with a live session: $(cat "$tmp/err")"
grep -q "recovering $d/journal-2-2.jsonl" "$tmp/err" || fail "a live session's journal was recovered: $(cat "$tmp/err")"
kill -9 "$child"; wait "$child" 2>/dev/null || true; child=""

# === Bad journals: one line naming the file and the problem, non-zero exit, no output.
bad() {  # bad NAME EXPECTED-TEXT [recover args...]
  local name="$1" want="$2"; shift 2
  rm -f "$tmp/bad.off" "$tmp/bad.json"
  if "$bin" recover "$@" -o "$tmp/bad.off" --report "$tmp/bad.json" 2> "$tmp/err"; then fail "$name accepted"; fi
  [ "$(wc -l < "$tmp/err")" -eq 1 ] || fail "$name: not one line: $(cat "$tmp/err")"
  grep -q -- "$want" "$tmp/err" || fail "$name: unclear message: $(cat "$tmp/err")"
  [ ! -e "$tmp/bad.off" ] && [ ! -e "$tmp/bad.json" ] || fail "$name: partial output"
}
bad missing "missing.jsonl: cannot open: No such file" "$tmp/missing.jsonl"
bad directory "$tmp: is a directory" "$tmp"
: > "$tmp/empty.jsonl"
bad empty "empty.jsonl:1: empty stroke log" "$tmp/empty.jsonl"
{ head -n 50 "$log"; echo '{"t":1e9,"type":"pen","x":'; head -n 60 "$log" | tail -n 10; } > "$tmp/broken.jsonl"
bad "broken line" "broken.jsonl:51: bad JSON" "$tmp/broken.jsonl"
printf '{"format":"planesketch-stroke-log","version":1' > "$tmp/torn-header.jsonl"
bad "torn header" "torn-header.jsonl:1: truncated header line" "$tmp/torn-header.jsonl"
cp "$log" "$tmp/unreadable.jsonl" && chmod 000 "$tmp/unreadable.jsonl"
if [ "$(id -u)" -ne 0 ]; then bad unreadable "unreadable.jsonl: cannot open: Permission denied" "$tmp/unreadable.jsonl"; fi
echo "journal kill test ok in $((SECONDS - start)) s"
