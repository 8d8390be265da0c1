#!/usr/bin/env bash
# ctest foxglove_bridge_live: `uavmot foxglove` beside the running chain with two viewers at once:
#   1. bridge_client.mjs, made of Foxglove's npm packages: every advertised channel subscribed,
#      every message decoded, Foxglove messages validated against @foxglove/schemas;
#   2. viewer_page.js in headless Chromium (screenshot.mjs): the image with its annotations drawn,
#      saved as OUT_DIR/image_panel.png (docs/foxglove_image_panel.png is one of these);
# then the recording the chain's recorder made, checked the same way (check_recording.mjs); and
# the bridge's bad-input errors. Installs the pinned node packages on first use.
#   run_bridge.sh BIN_DIR SOURCE_DIR OUT_DIR
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bin=$1
src=$2
out=$3
domain=63
source "$here/../support/node_packages.sh"
require_tools foxglove_bridge_live node npm /usr/bin/chromium
install_node_packages "$here"
rm -rf "$out"
mkdir -p "$out"
pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done; }
trap cleanup EXIT

expect_failure() {  # NAME EXPECTED_TEXT COMMAND...: must exit non-zero and say EXPECTED_TEXT
  local name=$1 text=$2
  shift 2
  if "$@" >"$out/$name.log" 2>&1; then echo "FAIL: $name exited 0" >&2; exit 1; fi
  grep -q -- "$text" "$out/$name.log" || { echo "FAIL: $name did not say '$text':" >&2; cat "$out/$name.log" >&2; exit 1; }
  echo "ok: $name -> $(tail -1 "$out/$name.log")"
}
expect_failure bad_port "not in range" "$bin/uavmot-foxglove" --port 70000
expect_failure unknown_topic "matches no uavmot topic" "$bin/uavmot-foxglove" --topics uavmot/no_such_topic --domain $domain
expect_failure bad_address "is not an IP address" "$bin/uavmot-foxglove" --address localhost:1 --domain $domain

# --downlink serves the link's topics (their schemas flatten and advertise); no link runs here.
"$bin/uavmot-foxglove" --downlink --port 0 --domain $domain --duration 1 >"$out/downlink.log" 2>&1 ||
  { echo "FAIL: uavmot foxglove --downlink:" >&2; cat "$out/downlink.log" >&2; exit 1; }
grep -q "serving 3 link topics" "$out/downlink.log" || { echo "FAIL: --downlink serves:" >&2; cat "$out/downlink.log" >&2; exit 1; }

"$bin/uavmot-sim" --preset paper --seed 1 --frames 60 --out "$out/paper" >"$out/sim.log" 2>&1
gsd=$(sed -n 's/^gsd=//p' "$out/paper/seqinfo.ini")
# Normal priority: at the default (idle) a bridge beside other busy tests could wait seconds for
# CPU time and miss the short chain; this test is about what the viewers receive.
"$bin/uavmot-foxglove" --port 0 --domain $domain --transport local --gsd "$gsd" --fps 25 --cpu-priority normal >"$out/bridge.log" 2>&1 &
bridge=$!
pids+=($bridge)
for _ in $(seq 100); do grep -q "serving" "$out/bridge.log" && break; sleep 0.1; done
port=$(sed -n 's/.*ws:\/\/127\.0\.0\.1:\([0-9]*\).*/\1/p' "$out/bridge.log" | head -1)
[[ -n "$port" ]] || { echo "FAIL: the bridge did not start:" >&2; cat "$out/bridge.log" >&2; exit 1; }
expect_failure port_in_use "in use" "$bin/uavmot-foxglove" --port "$port" --domain $domain

node "$here/bridge_client.mjs" "ws://127.0.0.1:$port" --ready "$out/ready" --done "$out/done" --expect 9 --require-kmh \
  --layout "$src/docs/foxglove_layout.json" \
  --summary "$out/viewer.json" >"$out/viewer.log" 2>&1 &
viewer=$!
pids+=($viewer)
node "$here/screenshot.mjs" "ws://127.0.0.1:$port" --ready "$out/page_ready" --done "$out/done" --png "$out/image_panel.png" \
  >"$out/page.log" 2>&1 &
page=$!
pids+=($page)
for _ in $(seq 600); do [[ -f "$out/ready" && -f "$out/page_ready" ]] && break; sleep 0.1; done
[[ -f "$out/ready" ]] || { echo "FAIL: the viewer did not subscribe:" >&2; cat "$out/viewer.log" >&2; exit 1; }
[[ -f "$out/page_ready" ]] || { echo "FAIL: the browser viewer did not subscribe:" >&2; cat "$out/page.log" >&2; exit 1; }

# The chain with its recorder (which writes the Foxglove channels by default).
"$bin/uavmot" launch "$src/bringup/local.yaml" --input "$out/paper" --out "$out/chain" --set domain=$domain \
  --set record=true >"$out/launch.log" 2>&1 || { echo "FAIL: the chain failed:" >&2; tail -30 "$out/launch.log" >&2; exit 1; }
touch "$out/done"
# The bridge, started before this lossless chain, must not let a writer start before its lossless
# readers: the recorder has every sample (uavmot foxglove subscribes once each writer has published).
for topic in frames motion segmentation tracks; do
  grep -q "uavmot/$topic: 61 samples; stream uav1: frames 1..60, 0 missing" "$out/launch.log" ||
    { echo "FAIL: the recorder missed samples of uavmot/$topic:" >&2; grep "\[record" "$out/launch.log" >&2; exit 1; }
done
viewer_rc=0 page_rc=0
wait $viewer || viewer_rc=$?
wait $page || page_rc=$?
cat "$out/viewer.log" "$out/page.log"
kill -TERM $bridge
bridge_rc=0
wait $bridge || bridge_rc=$?
tail -2 "$out/bridge.log"
[[ $viewer_rc == 0 ]] || { echo "FAIL: the viewer's checks failed" >&2; exit 1; }
[[ $page_rc == 0 ]] || { echo "FAIL: the browser viewer's checks failed" >&2; exit 1; }
[[ $bridge_rc == 0 ]] || { echo "FAIL: the bridge exited $bridge_rc" >&2; exit 1; }
grep -q "2 viewers served" "$out/bridge.log" || { echo "FAIL: the bridge did not count its viewer" >&2; exit 1; }

node "$here/check_recording.mjs" "$out/chain/chain.mcap" --require-kmh
