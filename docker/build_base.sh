#!/bin/sh
# Builds the uavmot base image without a registry: a minimal Debian bookworm root file system
# (debootstrap) with the runtime libraries the programs in BUILD_DIR/bin need
# (docker/runtime_packages.sh), imported into podman as localhost/uavmot-base.
#   docker/build_base.sh [BUILD_DIR]          (root; podman, debootstrap)
# The image is labelled with a hash of its package list and of `recipe` below; when both are
# unchanged the existing image is kept, so CI debootstraps only when the list changes.
# Set UAVMOT_BASE_REBUILD=1 to rebuild anyway; UAVMOT_CONTAINER_ENGINE=docker to import into
# Docker instead (same commands; not tried here, there is no Docker engine on this machine).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build_dir=${1:-$here/../build}
name=${UAVMOT_BASE_IMAGE:-localhost/uavmot-base}
engine=${UAVMOT_CONTAINER_ENGINE:-podman}
mirror=${UAVMOT_DEBIAN_MIRROR:-http://deb.debian.org/debian}
security_mirror=${UAVMOT_DEBIAN_SECURITY_MIRROR:-http://deb.debian.org/debian-security}

recipe=1  # bump when the steps below change what the image holds
packages=$(sh "$here/runtime_packages.sh" "$build_dir")
key=$(printf 'recipe %s\n%s\n' "$recipe" "$packages" | sha256sum | cut -c1-16)
current=$($engine image inspect --format '{{index .Config.Labels "uavmot.base.key"}}' "$name" 2>/dev/null || true)
if [ "$current" = "$key" ] && [ "${UAVMOT_BASE_REBUILD:-0}" != 1 ]; then
  echo "build_base: $name is up to date (key $key)"
  exit 0
fi

echo "build_base: building $name (key $key): $(echo $packages)"
rootfs=$(mktemp -d /tmp/uavmot-rootfs.XXXXXX)
log=$(mktemp /tmp/uavmot-base-log.XXXXXX)
cleanup() {
  umount "$rootfs/proc" 2>/dev/null || true
  rm -rf "$rootfs" "$log"
}
trap cleanup EXIT INT TERM
# Quiet unless a step fails: then its whole output.
step() {
  "$@" >"$log" 2>&1 || { cat "$log" >&2; echo "build_base: failed: $*" >&2; exit 1; }
}
step debootstrap --variant=minbase bookworm "$rootfs" "$mirror"
# The same suites as the build host, so library versions (and sonames) match the binaries.
cat > "$rootfs/etc/apt/sources.list" <<EOF
deb $mirror bookworm main
deb $mirror bookworm-updates main
deb $security_mirror bookworm-security main
EOF
mount -t proc proc "$rootfs/proc"
step chroot "$rootfs" /usr/bin/env DEBIAN_FRONTEND=noninteractive apt-get update
# shellcheck disable=SC2086
step chroot "$rootfs" /usr/bin/env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends $packages
step chroot "$rootfs" apt-get clean
umount "$rootfs/proc"
rm -rf "$rootfs/var/lib/apt/lists/"* "$rootfs/var/cache/apt/"*.bin "$rootfs/usr/share/doc" "$rootfs/usr/share/man"
tar -C "$rootfs" -c . | $engine import -q --change "LABEL uavmot.base.key=$key" --change 'CMD ["/bin/bash"]' - "$name" >/dev/null
echo "build_base: imported $name ($($engine image inspect --format '{{.Size}}' "$name") bytes)"
