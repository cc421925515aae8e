#!/usr/bin/env bash
# Installs the Debian 12 packages Minecrappy builds and tests with, only those that are missing.
# Runs as root, or through sudo when it is available. Nothing else is downloaded, ever.
set -euo pipefail

packages=(
  cmake ninja-build g++ clang-14 pkg-config
  libglfw3-dev libglew-dev libglm-dev libimgui-dev libstb-dev libegl-dev
  libosmesa6 libegl-mesa0 libgl1-mesa-dri
  libcli11-dev nlohmann-json3-dev libboost-math-dev libsqlite3-dev libtomlplusplus-dev
  googletest libgtest-dev libbenchmark-dev
  libglx-mesa0 xvfb xdotool xauth
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "setup: installing ${missing[*]}"
sudo=()
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then sudo=(sudo); else
    echo "setup: these packages are missing and this is not root (no sudo): ${missing[*]}" >&2
    exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
