#!/usr/bin/env bash
# Installs tripath's build dependencies from Debian's packages, plus any package named as an
# argument. Idempotent and quick when everything is already present: apt is only touched when a
# package is missing.
set -euo pipefail
packages=(build-essential cmake pkg-config
  libembree-dev libopenexr-dev libopenimageio-dev libtinygltf-dev nlohmann-json3-dev
  libbenchmark-dev libgtest-dev libtbb-dev libcli11-dev libfmt-dev
  fonts-dejavu-core  # the labels of `tripath compare`'s charts and side-by-side images
  libglm-dev  # the glTF loader's node transforms: 4×4 matrices and quaternions in double precision
  libcairo2-dev  # draws `tripath compare`'s chart once, onto an SVG and an image surface
  libopenmpi-dev openmpi-bin  # distributed rendering under mpirun (docs/distributed.md)
  pybind11-dev python3-dev python3-numpy python3-pytest  # the Python module and its tests (docs/python.md)
  "$@")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
sudo_cmd=()
[ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
echo "installing: ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
