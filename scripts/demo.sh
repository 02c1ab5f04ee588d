#!/usr/bin/env bash
# Quick start 1: install what is missing, build, and run the headline demo headless.
# Writes out/hanging_thread/: data (CSV, ParaView .pvd/.vtp), timing.json, pictures (PNG: frames,
# a contact sheet, plots of the motion and the energy) and a video (video.avi).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
cd "$root"
./build/apps/filum run apps/scenes/hanging_thread.json --out out/hanging_thread --render
/usr/bin/python3 apps/tools/plot_run.py out/hanging_thread  # Debian's python3, which has python3-matplotlib
