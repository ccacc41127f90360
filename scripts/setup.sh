#!/usr/bin/env bash
# Installs the Debian packages osd_cull needs when any is missing (idempotent; silent
# when nothing is missing), then configures and builds into build/ (or $OSD_CULL_BUILD_DIR).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

mapfile -t wanted < <(grep -v '^\s*#' "$root/scripts/packages.txt" | sed '/^\s*$/d')
missing=()
for p in "${wanted[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "osd_cull setup: installing Debian packages: ${missing[*]}" >&2
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo=sudo
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# OSD_CULL_SANITIZE=1: the ASan + UBSan build (as the CMake preset "asan") in build-asan/.
sanitize=()
build_type=Release
default_build=$root/build
if [ "${OSD_CULL_SANITIZE:-0}" = "1" ]; then
  sanitize=(-DOSD_CULL_SANITIZE=ON -DOSD_CULL_BUILD_BENCHMARKS=OFF)
  build_type=RelWithDebInfo
  default_build=$root/build-asan
fi
build=${OSD_CULL_BUILD_DIR:-$default_build}
werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
if [ ! -f "$build/CMakeCache.txt" ]; then
  echo "osd_cull setup: configuring $build" >&2
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=$build_type -DOSD_CULL_WERROR=$werror \
    "${sanitize[@]}" "${launcher[@]}" >/dev/null
fi
echo "osd_cull setup: building (this takes a few minutes the first time)" >&2
cmake --build "$build" -j"$(nproc)"
