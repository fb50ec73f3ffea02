#!/bin/sh
# Installs the system packages wingman needs on Debian or Ubuntu, those listed in
# scripts/packages.txt (a software Vulkan adapter for the renderer where there is no GPU, a
# TrueType font for the plots' labels). Runs apt-get directly as root (a container, CI), through
# sudo otherwise. `sh scripts/setup.sh --list` prints the packages instead.
set -eu
packages=$(grep -v '^#' "$(dirname "$0")/packages.txt")
if [ "${1:-}" = "--list" ]; then
    echo $packages
    exit 0
fi
if [ "$(id -u)" -eq 0 ]; then
    as_root=""
elif command -v sudo >/dev/null 2>&1; then
    as_root="sudo"
else
    echo "scripts/setup.sh: run it as root, or install sudo" >&2
    exit 1
fi
$as_root apt-get update
# shellcheck disable=SC2086 # one word a package
$as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends $packages
