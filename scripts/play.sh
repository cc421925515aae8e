#!/usr/bin/env bash
# Sets up, builds and starts Minecrappy. With a display it opens the game window (extra arguments go to
# the game); without one it renders the demo scene off-screen and prints where the PNG is.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh --target minecrappy
if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; then
  exec build/minecrappy "$@"
fi
echo "No display found: rendering the demo scene off-screen instead."
build/minecrappy --headless --ticks 120 --size 1280x720 --screenshot build/minecrappy-demo.png "$@"
echo "Demo frame: $PWD/build/minecrappy-demo.png"
