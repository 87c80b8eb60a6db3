#!/usr/bin/env bash
# Installs the Debian 12 packages quadra builds against, only those missing.
# With --farm, only the packages of the render-farm test instead
# (tests/farm/slurm_farm_test.sh): Slurm and MUNGE, which a build never needs
# and which enable system services where systemd runs.
set -euo pipefail
# ninja-build: the generator scripts/build.sh picks (one progress line, both
# cores busy to the end). libosmesa6-dev: Mesa's llvmpipe for comparisons
# (quadra-llvmpipe, `quadra report frames`); libopenimageio-dev: OpenImageIO's
# TextureSystem for `quadra report textures` (the module quadra_oiio_peer.so,
# loaded only by that report). quadra itself links neither. clang and libclang-rt-14-dev (which
# holds libFuzzer): the fuzz targets (scripts/fuzz.sh). openimageio-tools
# (iinfo) and openexr (exrheader): the test that other tools read quadra's
# EXR AOVs and header (AovsCli.WritesTheChannelsOtherToolsRead).
# python3-pybind11, python3-dev and python3-numpy: the Python module
# (python/, built for /usr/bin/python3) and its test; python3-venv and
# python3-pip: `pip install .` into a virtual environment (pyproject.toml,
# the PipInstall test).
packages=(build-essential cmake ninja-build pkg-config libtbb-dev libxsimd-dev libglm-dev libtinygltf-dev
  libstb-dev nlohmann-json3-dev libopenexr-dev libimath-dev libpng-dev libjpeg62-turbo-dev libbenchmark-dev
  libgtest-dev libosmesa6-dev libopenimageio-dev clang-format git clang libclang-rt-14-dev
  openimageio-tools openexr python3-pybind11 python3-dev python3-numpy python3-venv python3-pip)
if [ "${1:-}" = --farm ]; then
  packages=(slurm-wlm munge)
elif (($#)); then
  echo "install-deps.sh: unknown argument '$1' (--farm or none)" >&2
  exit 1
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "quadra: installing ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
