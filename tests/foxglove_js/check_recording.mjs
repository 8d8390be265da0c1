// Reads the Foxglove-schema channels of a `uavmot record` recording (uavmot/foxglove/*) with the
// official MCAP reader and decodes every message with Foxglove's OMG IDL deserializer from the
// IDL the channel's schema carries; validates each against @foxglove/schemas' definitions and
// checks the channels the Image panel needs are there: the image, and tracks with labels.
//   node check_recording.mjs RECORDING.mcap [--require-kmh]

import { open, stat } from "node:fs/promises";

import { McapIndexedReader } from "@mcap/core";
import { loadDecompressHandlers } from "@mcap/support";

import { idlFieldsMatch, makeChecker, makeDecoder, validateFoxglove } from "./foxglove_checks.mjs";

const [file, ...rest] = process.argv.slice(2);
if (!file) {
  console.error("usage: node check_recording.mjs RECORDING.mcap [--require-kmh]");
  process.exit(2);
}
const t = makeChecker();
const handle = await open(file, "r");
const size = (await stat(file)).size;
try {
  const reader = await McapIndexedReader.Initialize({
    readable: {
      size: async () => BigInt(size),
      read: async (offset, length) => {
        const buffer = new Uint8Array(Number(length));
        await handle.read(buffer, 0, Number(length), Number(offset));
        return buffer;
      },
    },
    decompressHandlers: await loadDecompressHandlers(),
  });
  const decoders = new Map();
  const counts = {};
  for (const channel of reader.channelsById.values()) {
    if (!channel.topic.startsWith("uavmot/foxglove/")) continue;
    const schema = reader.schemasById.get(channel.schemaId);
    const text = new TextDecoder().decode(schema.data);
    t.check(channel.messageEncoding === "cdr" && schema.encoding === "omgidl", `${channel.topic}: cdr + omgidl`);
    for (const error of idlFieldsMatch(schema.name, text)) t.check(false, `${channel.topic}: ${error}`);
    decoders.set(channel.id, { topic: channel.topic, schema: schema.name, decoder: makeDecoder(schema.name, text) });
    counts[channel.topic] = 0;
  }
  for (const topic of ["image", "tracks", "regions", "features"]) {
    t.check(`uavmot/foxglove/${topic}` in counts, `no uavmot/foxglove/${topic} channel`);
  }
  let labels = 0;
  let kmh = 0;
  for await (const message of reader.readMessages({ topics: Object.keys(counts) })) {
    const d = decoders.get(message.channelId);
    let value;
    try {
      value = d.decoder.readMessage(message.data);
    } catch (e) {
      t.check(false, `${d.topic}#${message.sequence}: does not decode: ${e.message}`);
      continue;
    }
    counts[d.topic]++;
    for (const error of validateFoxglove(value, d.schema)) t.check(false, `${d.topic}#${message.sequence}: ${error}`);
    if (d.topic === "uavmot/foxglove/tracks") {
      labels += value.texts.length;
      kmh += value.texts.filter((x) => / km\/h$/.test(x.text)).length;
    }
  }
  for (const [topic, n] of Object.entries(counts)) t.check(n > 0, `${topic}: no message`);
  t.check(labels > 0, "no track label");
  if (rest.includes("--require-kmh")) t.check(kmh > 0, "no track label in km/h");
  console.log(`${file}: ${JSON.stringify(counts)}; ${labels} track labels (${kmh} in km/h)`);
} catch (error) {
  t.check(false, error.stack ?? String(error));
} finally {
  await handle.close();
}
console.log(`${t.passed} passed, ${t.failed} failed`);
process.exit(t.failed === 0 ? 0 : 1);
