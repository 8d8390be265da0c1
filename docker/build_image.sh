#!/bin/sh
# Builds localhost/uavmot from the programs in BUILD_DIR/bin: the base image first (kept when
# its package list is unchanged, docker/build_base.sh), then a small build context with only
# the programs (docker/image_programs.sh) and bringup/, so the build tree is not sent to podman.
#   docker/build_image.sh [BUILD_DIR]          (root; podman, debootstrap)
# Podman here needs runc and raised ulimits (docker/containers.conf); CONTAINERS_CONF is set to
# it unless already set.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build_dir=$(cd "${1:-$here/../build}" && pwd)
export CONTAINERS_CONF=${CONTAINERS_CONF:-$here/containers.conf}
name=${UAVMOT_IMAGE:-localhost/uavmot}
engine=${UAVMOT_CONTAINER_ENGINE:-podman}  # docker works the same way (not tried here)

sh "$here/build_base.sh" "$build_dir"
context=$(mktemp -d /tmp/uavmot-image.XXXXXX)
trap 'rm -rf "$context"' EXIT INT TERM
mkdir "$context/bin"
cp $(sh "$here/image_programs.sh" "$build_dir/bin") "$context/bin/"
strip --strip-unneeded "$context"/bin/* 2>/dev/null || true
cp -a "$here/../bringup" "$context/bringup"
previous=$($engine image inspect --format '{{.Id}}' "$name" 2>/dev/null || true)
$engine build -q -t "$name" --build-arg "BASE=${UAVMOT_BASE_IMAGE:-localhost/uavmot-base}" -f "$here/Dockerfile" "$context" >/dev/null
# The image it replaces is left without a name (760 MB each build); remove it unless a container
# still uses it.
current=$($engine image inspect --format '{{.Id}}' "$name")
if [ -n "$previous" ] && [ "$previous" != "$current" ]; then
  $engine rmi "$previous" >/dev/null 2>&1 || true
fi
echo "build_image: built $name ($($engine image inspect --format '{{.Size}}' "$name") bytes)"
