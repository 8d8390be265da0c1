#!/bin/sh
# Builds the uavmot base image without a registry: a minimal Debian bookworm root file system
# (debootstrap) with the runtime libraries, imported into podman as `uavmot-base`.
#   sudo docker/build_base.sh [IMAGE_NAME]
# Then: podman build -t uavmot -f docker/Dockerfile .   (needs build/ with the binaries)
set -eu
name=${1:-uavmot-base}
rootfs=$(mktemp -d /tmp/uavmot-rootfs.XXXXXX)
trap 'rm -rf "$rootfs"' EXIT
debootstrap --variant=minbase bookworm "$rootfs" http://deb.debian.org/debian
chroot "$rootfs" apt-get install -y --no-install-recommends \
  libfastrtps2.9 libfastcdr1 libopencv-core406 libopencv-imgproc406 libopencv-imgcodecs406 libopencv-videoio406 \
  libopencv-video406 libopencv-calib3d406 libopencv-features2d406 libceres3 libyaml-cpp0.7 libspdlog1.10 libfmt9 \
  libzstd1 liblz4-1 iproute2 fastdds-tools
chroot "$rootfs" apt-get clean
tar -C "$rootfs" -c . | podman import - "$name"
echo "imported $name"
