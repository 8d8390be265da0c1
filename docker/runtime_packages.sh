#!/bin/sh
# Prints the Debian packages that hold the shared libraries the uavmot programs in BUILD_DIR/bin
# link against directly (apt brings their own dependencies), one per line, sorted, plus the
# tools the profiles start. This list is what the base image installs, and its hash decides
# when the base image must be rebuilt (docker/build_base.sh).
#   docker/runtime_packages.sh [BUILD_DIR]
set -eu
build_dir=${1:-build}
bin="$build_dir/bin"
[ -x "$bin/uavmot" ] || { echo "$0: no uavmot programs in $bin (build first)" >&2; exit 1; }

# Programs the image carries (docker/build_image.sh copies the same list).
programs=$(sh "$(dirname "$0")/image_programs.sh" "$bin")

sonames=$(for p in $programs; do readelf -d "$p" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p'; done | sort -u)
paths=""
for so in $sonames; do
  path=$(ldconfig -p | awk -v s="$so" '$1 == s && /x86-64/ { print $NF; exit }')
  [ -n "$path" ] || { echo "$0: $so is not known to ldconfig" >&2; exit 1; }
  paths="$paths $(realpath "$path")"
done
# Merged /usr: dpkg may know a library under /lib rather than /usr/lib; ask for both spellings.
# Every library must belong to some package, or the image would miss it.
packages=""
for p in $paths; do
  owner=$(dpkg -S "$p" 2>/dev/null || dpkg -S "${p#/usr}" 2>/dev/null) || {
    echo "$0: no Debian package holds $p" >&2
    exit 1
  }
  packages="$packages ${owner%%:*}"
done
# fastdds-tools: fast-discovery-server for links without multicast; iproute2: `ip` for diagnosis.
echo $packages fastdds-tools iproute2 | tr ' ' '\n' | sort -u
