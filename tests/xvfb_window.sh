# Sourced by the shell tests that run the window under xvfb-run on lavapipe
# (app_session_window_test.sh, app_window_guides_test.sh): skips the test without xvfb-run, and
# gives `bin`, `src`, a temporary directory `tmp` (removed on exit), `fail MESSAGE` and
# `win ARGS...` (the window at 640x400 without the panel, with a 300 s timeout).
set -euo pipefail
bin="${PLANESKETCH_BINARY:?}"
src="${PLANESKETCH_SOURCE_DIR:?}"
if ! command -v xvfb-run >/dev/null 2>&1; then echo "skipped: no xvfb-run"; exit 0; fi
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
win() { timeout 300 xvfb-run -a -s '-screen 0 1280x800x24' "$bin" window --no-panel --size 640x400 "$@"; }
