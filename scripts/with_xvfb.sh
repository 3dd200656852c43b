#!/usr/bin/env bash
# Runs a command against a private Xvfb server, which picks a free display
# itself (-displayfd) and is stopped afterwards:
#   scripts/with_xvfb.sh pvpython scripts/paraview_render.py OUT.xdmf -o frame.png
# -noreset: by default Xvfb resets when its last client disconnects, and a
# pvpython that connected during the reset aborted ("bad X server
# connection"; 2 of 6 renders under `xvfb-run -a`, 0 of 12 with -noreset).
set -euo pipefail
command -v Xvfb >/dev/null || { echo "with_xvfb: Xvfb is not installed (bash scripts/setup.sh paraview)" >&2; exit 77; }
fifo_dir="$(mktemp -d)"
trap 'rm -rf "$fifo_dir"' EXIT
Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp -noreset 3>"$fifo_dir/display" 2>"$fifo_dir/log" &
xvfb=$!
for _ in $(seq 200); do
  [ -s "$fifo_dir/display" ] && break
  kill -0 "$xvfb" 2>/dev/null || { cat "$fifo_dir/log" >&2; exit 1; }
  sleep 0.05
done
[ -s "$fifo_dir/display" ] || { echo "with_xvfb: Xvfb did not start" >&2; kill "$xvfb"; exit 1; }
rc=0
DISPLAY=":$(head -1 "$fifo_dir/display")" "$@" || rc=$?
kill "$xvfb" 2>/dev/null || true
wait "$xvfb" 2>/dev/null || true
exit $rc
