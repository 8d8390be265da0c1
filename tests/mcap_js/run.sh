#!/usr/bin/env bash
# ctest mcap_official_reader: writes the sample recordings, then checks them with the official
# MCAP reader from npm. Installs the pinned node packages on first use.
#   run.sh MAKE_SAMPLE_BINARY MCAP_INFO_BINARY OUT_DIR IDL_DIR
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
make_sample=$1
mcap_info=$2
out=$3
idl=$4
source "$here/../support/node_packages.sh"
require_tools mcap_official_reader node npm
install_node_packages "$here"
rm -rf "$out"
"$make_sample" "$out" "$idl"
node "$here/validate.mjs" "$out" "$mcap_info"
