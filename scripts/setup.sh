#!/bin/sh
# Installs the system packages wingman needs on Debian or Ubuntu: a software Vulkan adapter
# (Mesa's lavapipe) and its loader for the renderer where there is no GPU, and a TrueType font
# for the plots' labels. Runs apt-get directly as root (a container has no sudo), through sudo
# otherwise.
set -eu
if [ "$(id -u)" -eq 0 ]; then
    as_root=""
elif command -v sudo >/dev/null 2>&1; then
    as_root="sudo"
else
    echo "scripts/setup.sh: run it as root, or install sudo" >&2
    exit 1
fi
$as_root apt-get update
$as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
    mesa-vulkan-drivers libvulkan1 fonts-dejavu-core
