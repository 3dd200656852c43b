#!/usr/bin/env bash
# Renders a frame of an atssim result with ParaView (pvpython) under Xvfb:
#   scripts/render_paraview.sh OUT.xdmf --frame 60 -o frame.png
# Installs Debian's paraview and xvfb when missing (scripts/setup.sh paraview).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bash "$here/setup.sh" paraview
exec xvfb-run -a -s "-screen 0 1280x1024x24" pvpython "$here/paraview_render.py" "$@"
