#!/usr/bin/env bash
# A chain on the default `local` transport must be closed to the LAN. Two network namespaces joined
# by a veth pair stand for the chain's host and another host on its LAN; the other host also gets
# its own /dev/shm, as a separate machine has. A component runs on the chain's host; the other host
# looks for it with `uavmot status` over UDP (as anyone on the LAN could).
#   --transport udp    (positive control) the other host sees the component
#   --transport local  it sees nothing, while a second `local` participant on the chain's host does
# Needs root (ip netns, mount); fails, not skips, without it.
#   lan_exposure_test.sh BIN_DIR
set -euo pipefail
bin=${1:?usage: lan_exposure_test.sh BIN_DIR}
if [[ $(id -u) != 0 ]]; then echo "lan_exposure_test: needs root (ip netns, mount)" >&2; exit 1; fi
command -v ip >/dev/null && command -v unshare >/dev/null || { echo "lan_exposure_test: needs ip and unshare" >&2; exit 1; }
host=uavmot_lan_host_$$ lan=uavmot_lan_other_$$ domain=43
work=$(mktemp -d)
sink_pid=""
cleanup() {
  if [[ -n $sink_pid ]]; then kill "$sink_pid" 2>/dev/null || true; wait "$sink_pid" 2>/dev/null || true; fi
  ip netns del "$host" 2>/dev/null || true
  ip netns del "$lan" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
ip netns add "$host"
ip netns add "$lan"
ip link add "vlh$$" type veth peer name "vlo$$"
ip link set "vlh$$" netns "$host"
ip link set "vlo$$" netns "$lan"
ip -n "$host" addr add 10.203.0.1/24 dev "vlh$$"
ip -n "$lan" addr add 10.203.0.2/24 dev "vlo$$"
for ns in "$host" "$lan"; do ip -n "$ns" link set lo up; done
ip -n "$host" link set "vlh$$" up
ip -n "$lan" link set "vlo$$" up

# Prints what `uavmot status --once` saw from the other host (its own /dev/shm, UDP).
status_from_lan() {
  ip netns exec "$lan" unshare -m sh -c \
    "mount -t tmpfs none /dev/shm && '$bin/uavmot-status' --once --wait 6 --domain $domain --transport udp" 2>&1 || true
}
# The same from the chain's host, on the default transport.
status_on_host() {
  ip netns exec "$host" "$bin/uavmot-status" --once --wait 6 --domain $domain 2>&1 || true
}
start_component() {  # TRANSPORT
  ip netns exec "$host" "$bin/uavmot-sink" --out "$work/sink_$1" --domain $domain --transport "$1" >"$work/sink_$1.log" 2>&1 &
  sink_pid=$!
  sleep 1
}
stop_component() {
  kill "$sink_pid"
  wait "$sink_pid" 2>/dev/null || true
  sink_pid=""
}
failed=0
check() {  # WHAT OUTPUT EXPECT(seen|unseen)
  local seen=unseen
  if grep -Eq '^\*? *sink ' <<<"$2"; then seen=seen; fi
  if [[ $seen == "$3" ]]; then
    echo "lan_exposure_test: ok: $1: sink $seen"
  else
    echo "lan_exposure_test: FAILED: $1: sink $seen, expected $3; status printed:"
    echo "$2"
    failed=1
  fi
}

start_component udp
check "udp component, from the LAN" "$(status_from_lan)" seen
stop_component

start_component local
check "local component, from the LAN" "$(status_from_lan)" unseen
check "local component, from its own host" "$(status_on_host)" seen
stop_component
exit $failed
