// A viewer of `uavmot foxglove` made of Foxglove's own npm packages: @foxglove/ws-protocol's
// FoxgloveClient connects (over the `ws` package), subscribes to every advertised channel and
// decodes every message with @foxglove/omgidl-serialization from the schema the channel carries;
// Foxglove-schema messages are validated against @foxglove/schemas' definitions.
//
//   node bridge_client.mjs URL --ready FILE --done FILE [--timeout S] [--expect N] [--require-kmh] [--summary OUT.json]
//   --ready: written once subscribed to every channel (the test then starts the chain)
//   --done:  the test creates it when the chain has finished; the client stops 2 s later
//   --expect: the number of channels the bridge must advertise
//   --require-kmh: some track label must read "km/h" (the bridge was given --gsd)
//   --layout FILE: a Foxglove layout (docs/foxglove_layout.json) whose every topic the bridge
//                  advertises and whose message paths name fields the decoded messages have
// Exits 1 when a channel got no message, a message did not decode or validate, or time ran out.

import { existsSync, readFileSync, writeFileSync } from "node:fs";

import wsProtocol from "@foxglove/ws-protocol";
import WebSocket from "ws";

const { FoxgloveClient } = wsProtocol;  // CommonJS: no named export for ESM

import { idlFieldsMatch, makeChecker, makeDecoder, validateFoxglove } from "./foxglove_checks.mjs";

const [url, ...rest] = process.argv.slice(2);
const option = (name, fallback) => (rest.includes(name) ? rest[rest.indexOf(name) + 1] : fallback);
const readyFile = option("--ready");
const doneFile = option("--done");
const timeoutS = Number(option("--timeout", "180"));
const expectChannels = Number(option("--expect", "0"));
const requireKmh = rest.includes("--require-kmh");
const summaryFile = option("--summary");
const layoutFile = option("--layout");
if (!url || !readyFile || !doneFile) {
  console.error("usage: node bridge_client.mjs URL --ready FILE --done FILE [--timeout S] [--expect N] [--require-kmh] [--summary OUT.json]");
  process.exit(2);
}

const t = makeChecker();
const channels = new Map();  // channel id -> {channel, decoder, count, errors}
const bySubscription = new Map();
let labels = 0;
let kmhLabels = 0;
let annotatedPolygons = 0;

const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
client.on("error", (e) => t.check(false, `client error: ${e.message}`));
client.on("serverInfo", (info) => console.log(`server ${info.name}`));
client.on("status", (s) => t.check(s.level < 2, `server status: ${s.message}`));
client.on("advertise", (advertised) => {
  for (const channel of advertised) {
    t.check(channel.encoding === "cdr", `${channel.topic}: encoding ${channel.encoding}`);
    t.check(channel.schemaEncoding === "omgidl", `${channel.topic}: schema encoding ${channel.schemaEncoding}`);
    let decoder;
    try {
      decoder = makeDecoder(channel.schemaName, channel.schema);
    } catch (e) {
      t.check(false, `${channel.topic}: schema ${channel.schemaName} does not parse: ${e.message}`);
      continue;
    }
    if (channel.schemaName.startsWith("foxglove::")) {
      for (const error of idlFieldsMatch(channel.schemaName, channel.schema)) t.check(false, `${channel.topic}: ${error}`);
    }
    channels.set(channel.id, { channel, decoder, count: 0 });
    bySubscription.set(client.subscribe(channel.id), channel.id);
  }
  console.log(`subscribed to ${channels.size} channels: ${[...channels.values()].map((c) => c.channel.topic).join(", ")}`);
  if (expectChannels === 0 || channels.size >= expectChannels) writeFileSync(readyFile, "subscribed\n");
});
client.on("message", ({ subscriptionId, data }) => {
  const entry = channels.get(bySubscription.get(subscriptionId));
  if (!entry) return t.check(false, `message for unknown subscription ${subscriptionId}`);
  let value;
  try {
    value = entry.decoder.readMessage(new Uint8Array(data.buffer, data.byteOffset, data.byteLength));
  } catch (e) {
    return t.check(false, `${entry.channel.topic}: message ${entry.count + 1} does not decode: ${e.message}`);
  }
  entry.count++;
  entry.sample ??= value;
  if (typeof value.component_name === "string") (entry.components ??= new Set()).add(value.component_name);
  const name = entry.channel.schemaName;
  if (name.startsWith("foxglove::")) {
    for (const error of validateFoxglove(value, name)) t.check(false, `${entry.channel.topic}#${entry.count}: ${error}`);
    if (name === "foxglove::ImageAnnotations" && entry.channel.topic.endsWith("/tracks")) {
      labels += value.texts.length;
      kmhLabels += value.texts.filter((x) => /^#\d+ \d+ km\/h$/.test(x.text)).length;
      annotatedPolygons += value.points.filter((p) => p.type === 2 && p.points.length === 4).length;
    }
    if (name === "foxglove::CompressedImage") t.check(value.format === "jpeg" && value.data[0] === 0xff && value.data[1] === 0xd8, "image is a JPEG");
  } else {
    t.check(typeof value.stream_id === "string", `${entry.channel.topic}: uavmot sample has a stream_id`);
  }
});

const start = Date.now();
let doneAt;
await new Promise((resolve) => {
  const timer = setInterval(() => {
    if (!doneAt && existsSync(doneFile)) doneAt = Date.now();
    if ((doneAt && Date.now() - doneAt > 2000) || Date.now() - start > timeoutS * 1000) {
      clearInterval(timer);
      resolve();
    }
  }, 100);
});
client.close();

t.check(doneAt !== undefined, `the chain did not finish within ${timeoutS} s`);
t.check(expectChannels === 0 || channels.size === expectChannels, `${channels.size} channels advertised, expected ${expectChannels}`);
for (const { channel, count } of channels.values()) t.check(count > 0, `${channel.topic}: no message received`);
t.check(annotatedPolygons > 0, "no track polygon (4-point LINE_LOOP) in uavmot/foxglove/tracks");
t.check(labels > 0, "no track label in uavmot/foxglove/tracks");
if (requireKmh) t.check(kmhLabels > 0, "no track label in km/h");
if (layoutFile) {
  // Every topic and message path the layout names, against what the bridge served.
  const layout = JSON.parse(readFileSync(layoutFile, "utf8"));
  const byTopic = new Map([...channels.values()].map((c) => [c.channel.topic, c]));
  const paths = [];
  for (const [id, config] of Object.entries(layout.configById)) {
    if (config.imageMode) {
      paths.push(config.imageMode.imageTopic);
      paths.push(...Object.keys(config.imageMode.annotations ?? {}));
    }
    if (config.paths) paths.push(...config.paths.map((p) => p.value));
    if (config.topicPath) paths.push(config.topicPath);
    t.check(layout.layout && JSON.stringify(layout.layout).includes(id), `layout: panel ${id} is placed`);
  }
  for (const path of paths) {
    const [, topic, filter, field] = /^([^.{]+)(\{[^}]*\})?(?:\.(\w+))?/.exec(path);
    const c = byTopic.get(topic);
    t.check(c, `layout: ${path}: the bridge does not advertise ${topic}`);
    if (!c?.sample) continue;
    if (filter) {
      const [, key, want] = /\{(\w+)=="([^"]*)"\}/.exec(filter);
      t.check(key in c.sample, `layout: ${path}: ${topic} has no field ${key}`);
      t.check(key !== "component_name" || c.components?.has(want), `layout: ${path}: no ${key} == ${want} seen`);
    }
    if (field) t.check(field in c.sample, `layout: ${path}: ${topic} has no field ${field}`);
  }
  console.log(`layout: ${paths.length} topics and message paths checked`);
}
const summary = Object.fromEntries([...channels.values()].map(({ channel, count }) => [channel.topic, count]));
console.log(`received: ${JSON.stringify(summary)}; ${labels} track labels (${kmhLabels} in km/h)`);
if (summaryFile) writeFileSync(summaryFile, JSON.stringify({ channels: summary, labels, kmhLabels }, null, 1));
console.log(`${t.passed} passed, ${t.failed} failed`);
process.exit(t.failed === 0 ? 0 : 1);
