#!/usr/bin/env bash
# Installs what Streamline Studio needs on a Debian machine, only what is missing:
# a Rust toolchain is assumed (rustup); Bevy's x11 and Vulkan libraries are loaded
# at run time, so no -dev headers are needed. For windows without a display (CI,
# servers) it adds a virtual X server and Mesa's software Vulkan (llvmpipe), and
# xdotool, with which the GUI tests drive a real pointer. With `--tests` (the
# README's test command) also what the tests check our files with: OpenSubdiv
# (libosd-dev, compiled into a small C++ oracle with g++) and a Python virtual
# environment with OpenCascade and USD (scripts/venv.sh), and the Khronos glTF
# validator in a node folder (scripts/node.sh).
set -euo pipefail

need=()
have() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"; }
pkgs=(libvulkan1 mesa-vulkan-drivers libx11-6 libxcursor1 libxrandr2 libxi6 libxkbcommon-x11-0 xvfb xauth xdotool)
tests=0; [ "${1:-}" = "--tests" ] && tests=1
((tests)) && pkgs+=(g++ libosd-dev)
for pkg in "${pkgs[@]}"; do
  have "$pkg" || need+=("$pkg")
done
if ((${#need[@]})); then
  echo "setup: installing ${need[*]}" >&2
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null
fi
command -v cargo >/dev/null || { echo "setup: cargo not found; install Rust 1.95 with rustup first" >&2; exit 1; }
if ((tests)); then bash "$(dirname "$0")/venv.sh"; bash "$(dirname "$0")/node.sh"; fi
