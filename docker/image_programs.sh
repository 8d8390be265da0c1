#!/bin/sh
# Prints the uavmot programs in BIN that the runtime image carries: every uavmot program except
# benchmarks, development tools and uavmot-view (it opens windows through highgui, which would
# bring GTK into the image; viewers run on a desktop, outside the containers).
#   docker/image_programs.sh BUILD_DIR/bin
set -eu
for p in "$1"/uavmot "$1"/uavmot-*; do
  case "$(basename "$p")" in
    *bench*|*-tables|uavmot-view) continue ;;
  esac
  [ -x "$p" ] && echo "$p"
done
