#!/bin/bash
# Installs the Debian 12 packages the project needs, when they are missing,
# and the packages named as arguments (those of one script only).
# libopenblas0-pthread replaces the reference BLAS behind deal.II and MUMPS
# (Debian alternatives): the direct solves become 2x (2D) to 5x (3D) faster.
set -euo pipefail
packages=(g++ cmake make libdeal.ii-dev libopenblas0-pthread openmpi-bin numdiff python3-matplotlib
          python3-paraview xvfb xauth "$@")
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "Installing: ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
