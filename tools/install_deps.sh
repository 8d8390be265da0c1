#!/usr/bin/env bash
# Installs every Debian package uavmot needs to build, test and demo. Idempotent.
set -euo pipefail

packages=(
  # build
  cmake ninja-build g++ ccache pkg-config
  # middleware: Fast DDS 2.9 and its code generator
  libfastrtps-dev libfastcdr-dev fastddsgen fastdds-tools
  # vision and estimation
  libopencv-dev libeigen3-dev libceres-dev ffmpeg
  # configuration, CLI, logging, JSON, compression
  libyaml-cpp-dev libcli11-dev libspdlog-dev libfmt-dev nlohmann-json3-dev libzstd-dev liblz4-dev
  # the Foxglove WebSocket bridge (uavmot foxglove): websocketpp on standalone asio
  libwebsocketpp-dev libasio-dev
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev
  # fuzzing (tools/fuzz.sh): clang 14 with libFuzzer and the sanitizer runtimes; llvm-symbolizer for
  # readable sanitizer stacks (GCC's ASan/UBSan/TSan runtimes for tools/sanitize.sh come with g++)
  clang libclang-rt-14-dev llvm
  # integration tests: network namespaces, firewall rules, process tools
  iproute2 nftables procps psmisc python3
  # containers: podman (runc: crun cannot set ulimits here), podman-compose, debootstrap for the base image
  podman runc podman-compose debootstrap
  # browser tests: the annotated mp4 plays in headless Chromium (tests/browser_js, playwright-core
  # drives Debian's /usr/bin/chromium; playwright's own browser download is not used)
  chromium
)

# MCAP validation (tests/mcap_js): node and npm run the official MCAP reader. Debian's nodejs
# and npm, unless a node with npm is already installed (another node package conflicts with
# Debian's npm, and either serves).
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  packages+=(nodejs npm)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "install_deps: all ${#packages[@]} packages present"
  exit 0
fi
echo "install_deps: installing ${#missing[@]} packages: ${missing[*]}"
if [[ $(id -u) -ne 0 ]]; then
  echo "install_deps: run as root (apt-get needs it)" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install_deps: done"
