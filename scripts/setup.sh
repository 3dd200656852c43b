#!/usr/bin/env bash
# Installs the Debian 12 packages atssim needs. Idempotent: does nothing when
# every package is already present. Needs root (or sudo) only when something
# is missing.
#
#   bash scripts/setup.sh                 # build, tests, scripts (CI runs this)
#   bash scripts/setup.sh paraview        # + ParaView's pvpython and Xvfb (~600 MB)
#   bash scripts/setup.sh slurm           # + a one-node Slurm cluster with munge
#   bash scripts/setup.sh fuzz            # + clang with libFuzzer (scripts/fuzz_scene.sh)
#   bash scripts/setup.sh check           # + fuzz, clang-tidy, clang-format (scripts/check.sh; CI)
#
# ParaView and Slurm are opt-in groups: they are large (ParaView pulls Qt,
# VTK and OpenMPI) or start daemons, and only the workflow scripts under
# scripts/ and the tests labelled `paraview`/`slurm` use them (those tests
# skip with a message when the group is missing).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev
  ocl-icd-opencl-dev opencl-c-headers opencl-clhpp-headers pocl-opencl-icd clinfo
  libtbb-dev libassimp-dev libyaml-cpp-dev
  libhdf5-dev hdf5-tools
  libcli11-dev catch2 libfmt-dev libspdlog-dev libbenchmark-dev
  python3 python3-h5py python3-matplotlib python3-numpy
  python3-meshio python3-jsonschema python3-yaml
  parallel time
  assimp-testmodels  # test data: the figure mesh of tests/app/test_figure_drape.cpp
)

for group in "$@"; do
  case "$group" in
    paraview) packages+=(paraview python3-paraview xvfb xauth) ;;
    slurm) packages+=(slurm-wlm munge) ;;
    fuzz) packages+=(clang libclang-rt-dev) ;;
    check) packages+=(clang libclang-rt-dev clang-tidy clang-format) ;;
    *) echo "atssim setup: unknown group '$group' (groups: paraview, slurm, fuzz, check)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "atssim setup: installing ${missing[*]}" >&2
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
# Another apt run (a second checkout's setup) holds the lock: wait for it.
apt_opts=(-o DPkg::Lock::Timeout=600)
"${sudo_cmd[@]}" apt-get "${apt_opts[@]}" update -qq
"${sudo_cmd[@]}" apt-get "${apt_opts[@]}" install -y -qq --no-install-recommends "${missing[@]}" >&2
