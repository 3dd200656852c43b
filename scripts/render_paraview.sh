#!/usr/bin/env bash
# Renders a frame of an atssim result with ParaView (pvpython) under Xvfb:
#   scripts/render_paraview.sh OUT.xdmf --frame 60 -o frame.png
# Installs Debian's paraview and xvfb when missing (scripts/setup.sh paraview).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bash "$here/setup.sh" paraview
exec bash "$here/with_xvfb.sh" pvpython "$here/paraview_render.py" "$@"
