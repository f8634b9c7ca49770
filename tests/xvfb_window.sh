# Sourced by the window tests (tests/app_*window_test.sh): strict mode, the binary and source
# tree from the environment, a skip without xvfb-run, a temporary directory removed at exit,
# fail MESSAGE, and win ARGS... (the window without its panel, 640x400, under xvfb-run).
set -euo pipefail
bin="${PLANESKETCH_BINARY:?}"
src="${PLANESKETCH_SOURCE_DIR:?}"
if ! command -v xvfb-run >/dev/null 2>&1; then echo "skipped: no xvfb-run"; exit 0; fi
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
win() { timeout 300 xvfb-run -a -s '-screen 0 1280x800x24' "$bin" window --no-panel --size 640x400 "$@"; }
