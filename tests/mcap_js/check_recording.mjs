// Reads a recording made by `uavmot record` with the official MCAP reader (@mcap/core, indexed
// and streaming) and decodes every message with Foxglove's OMG IDL deserializer from the IDL
// text in its schema; compares counts, schemas, channels and each message's frame index with
// what uavmot's C++ reader found (EXPECTED_JSON, written by the integration test).
//
//   node check_recording.mjs RECORDING.mcap EXPECTED_JSON
//   EXPECTED_JSON: {"topics": {"uavmot/motion": {"type": "uavmot::msg::MotionEstimate",
//                   "frame_index": [1, 2, ...]}, ...}}   (frame_index in sequence order)

import { readFile, open } from "node:fs/promises";

import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { loadDecompressHandlers } from "@mcap/support";
import { parseIDL } from "@foxglove/omgidl-parser";
import { MessageReader } from "@foxglove/omgidl-serialization";

const [file, expectedFile] = process.argv.slice(2);
if (!file || !expectedFile) {
  console.error("usage: node check_recording.mjs RECORDING.mcap EXPECTED_JSON");
  process.exit(2);
}
let passed = 0;
let failed = 0;
function check(condition, what) {
  if (condition) passed++;
  else {
    failed++;
    console.error(`FAIL: ${what}`);
  }
}

const expected = JSON.parse(await readFile(expectedFile, "utf8")).topics;
const bytes = await readFile(file);
const handle = await open(file, "r");
const decompressHandlers = await loadDecompressHandlers();
try {
  const reader = await McapIndexedReader.Initialize({
    readable: {
      size: async () => BigInt(bytes.length),
      read: async (offset, length) => {
        const buffer = new Uint8Array(Number(length));
        await handle.read(buffer, 0, Number(length), Number(offset));
        return buffer;
      },
    },
    decompressHandlers,
  });
  const stats = reader.statistics;
  // uavmot's own channels; the Foxglove-schema channels beside them (uavmot/foxglove/*) are
  // checked by tests/foxglove_js/check_recording.mjs.
  const uavmotChannels = [...reader.channelsById.values()].filter((c) => !c.topic.startsWith("uavmot/foxglove/"));
  check(uavmotChannels.length === Object.keys(expected).length,
    `${uavmotChannels.length} channels, expected ${Object.keys(expected).length}`);
  const decoders = new Map();
  for (const channel of uavmotChannels) {
    const want = expected[channel.topic];
    const schema = reader.schemasById.get(channel.schemaId);
    check(want != undefined, `channel ${channel.topic} expected`);
    check(channel.messageEncoding === "cdr", `${channel.topic}: message encoding cdr`);
    check(schema?.encoding === "omgidl", `${channel.topic}: schema encoding omgidl`);
    check(schema?.name === want?.type, `${channel.topic}: schema ${schema?.name} is ${want?.type}`);
    check(channel.metadata.get("type") === want?.type, `${channel.topic}: metadata type`);
    check(["RELIABLE", "BEST_EFFORT"].includes(channel.metadata.get("reliability")), `${channel.topic}: metadata reliability`);
    check(channel.metadata.has("durability") && channel.metadata.has("history"), `${channel.topic}: metadata QoS`);
    check(stats?.channelMessageCounts.get(channel.id) === BigInt(want?.frame_index.length ?? -1),
      `${channel.topic}: statistics count ${stats?.channelMessageCounts.get(channel.id)} == ${want?.frame_index.length}`);
    decoders.set(channel.id, new MessageReader(schema.name, parseIDL(new TextDecoder().decode(schema.data))));
  }

  let decoded = 0;
  let lastLogTime = -1n;
  let inOrder = true;
  for await (const message of reader.readMessages({ topics: uavmotChannels.map((c) => c.topic) })) {
    const channel = reader.channelsById.get(message.channelId);
    if (message.logTime < lastLogTime) inOrder = false;
    lastLogTime = message.logTime;
    const value = decoders.get(message.channelId).readMessage(message.data);
    const want = expected[channel.topic].frame_index[message.sequence - 1];
    const got = value.frame_index ?? value.last_frame_index;
    check(String(got) === String(want), `${channel.topic}#${message.sequence}: frame index ${got} == ${want}`);
    check(typeof value.stream_id === "string" && value.stream_id.length > 0, `${channel.topic}#${message.sequence}: stream_id`);
    decoded++;
  }
  check(inOrder, "messages in log-time order");
  let uavmotMessages = 0n;
  for (const c of uavmotChannels) uavmotMessages += stats?.channelMessageCounts.get(c.id) ?? 0n;
  check(BigInt(decoded) === uavmotMessages, `decoded ${decoded} of ${uavmotMessages} messages`);

  const stream = new McapStreamReader({ decompressHandlers, validateCrcs: true });
  stream.append(new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.byteLength));
  let streamed = 0;
  let sawFooter = false;
  for (let record; (record = stream.nextRecord());) {
    if (record.type === "Message" && decoders.has(record.channelId)) streamed++;
    if (record.type === "Footer") sawFooter = true;
  }
  check(stream.done() && sawFooter, "stream reader reached the footer");
  check(streamed === decoded, `stream reader saw ${streamed} of ${decoded} messages`);
  console.log(`${file}: ${decoded} messages on ${uavmotChannels.length} uavmot channels read and decoded, ${reader.chunkIndexes.length} chunks`);
} catch (error) {
  check(false, error.stack ?? String(error));
} finally {
  await handle.close();
}
console.log(`${passed} passed, ${failed} failed`);
process.exit(failed === 0 ? 0 : 1);
