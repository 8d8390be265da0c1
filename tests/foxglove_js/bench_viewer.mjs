// A light viewer for tools/bench/foxglove_bench.sh: @foxglove/ws-protocol's client subscribes to
// every channel `uavmot foxglove` advertises and counts messages and bytes (no decoding, so the
// benchmark measures the bridge, not the viewer's CPU).
//   node bench_viewer.mjs URL --ready FILE --done FILE [--prefix P]
//   --prefix: subscribe only to channels whose topic starts with P (uavmot/foxglove/: what the
//             Image panel with the layout's annotations takes, not the raw frames)
import { existsSync, writeFileSync } from "node:fs";

import wsProtocol from "@foxglove/ws-protocol";
import WebSocket from "ws";

const { FoxgloveClient } = wsProtocol;  // CommonJS: no named export for ESM
const [url, ...rest] = process.argv.slice(2);
const option = (name) => rest[rest.indexOf(name) + 1];
const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
let messages = 0;
let bytes = 0;
client.on("advertise", (channels) => {
  const prefix = rest.includes("--prefix") ? option("--prefix") : "";
  for (const c of channels) if (c.topic.startsWith(prefix)) client.subscribe(c.id);
  writeFileSync(option("--ready"), "subscribed\n");
});
client.on("message", ({ data }) => {
  messages++;
  bytes += data.byteLength;
});
const timer = setInterval(() => {
  if (existsSync(option("--done"))) {
    clearInterval(timer);
    client.close();
    console.log(`viewer: ${messages} messages, ${(bytes / 1048576).toFixed(1)} MiB`);
  }
}, 200);
