// Reads uavmot's sample recordings with the official MCAP reader (@mcap/core, indexed and
// streaming) and decodes every CDR payload with Foxglove's OMG IDL deserializer, comparing the
// values with what the C++ side serialized (expected.json from mcap_make_sample).
//
// Then checks the other direction (interop.mjs): the official writer's files read by uavmot.
//
//   node validate.mjs SAMPLE_DIR MCAP_INFO_BINARY

import { readFile, open } from "node:fs/promises";
import path from "node:path";

import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { loadDecompressHandlers } from "@mcap/support";
import { parseIDL } from "@foxglove/omgidl-parser";
import { MessageReader } from "@foxglove/omgidl-serialization";

import { checkInterop } from "./interop.mjs";

const dir = process.argv[2];
const mcapInfo = process.argv[3];
if (!dir || !mcapInfo) {
  console.error("usage: node validate.mjs SAMPLE_DIR MCAP_INFO_BINARY");
  process.exit(2);
}

let passed = 0;
let failed = 0;
function check(condition, what) {
  if (condition) {
    passed++;
  } else {
    failed++;
    console.error(`FAIL: ${what}`);
  }
}

// Expected JSON (64-bit integers as strings) against decoded values (bigint, typed arrays).
function matches(expected, actual, where, problems) {
  if (Array.isArray(expected)) {
    if (actual == undefined || typeof actual.length !== "number" || actual.length !== expected.length) {
      problems.push(`${where}: expected ${expected.length} elements, got ${actual?.length}`);
      return;
    }
    expected.forEach((e, i) => matches(e, actual[i], `${where}[${i}]`, problems));
  } else if (expected !== null && typeof expected === "object") {
    for (const [key, value] of Object.entries(expected)) matches(value, actual?.[key], `${where}.${key}`, problems);
  } else if (typeof expected === "string" && typeof actual === "bigint") {
    if (String(actual) !== expected) problems.push(`${where}: expected ${expected}, got ${actual}`);
  } else if (expected !== actual) {
    problems.push(`${where}: expected ${JSON.stringify(expected)}, got ${String(actual)}`);
  }
}

function fileReadable(handle, size) {
  return {
    size: async () => BigInt(size),
    read: async (offset, length) => {
      const buffer = new Uint8Array(Number(length));
      const { bytesRead } = await handle.read(buffer, 0, Number(length), Number(offset));
      if (bytesRead !== Number(length)) throw new Error(`short read at ${offset}`);
      return buffer;
    },
  };
}

const manifest = JSON.parse(await readFile(path.join(dir, "expected.json"), "utf8"));
const expectedTopics = manifest.expected.topics;
const decompressHandlers = await loadDecompressHandlers();

for (const [name, info] of Object.entries(manifest.files)) {
  const file = path.join(dir, name);
  const frames = info.frames;
  const bytes = await readFile(file);
  const handle = await open(file, "r");
  try {
    // --- Indexed reader: summary, statistics, chunk indexes, message indexes.
    const reader = await McapIndexedReader.Initialize({
      readable: fileReadable(handle, bytes.length),
      decompressHandlers,
    });
    const minChunks = info.min_chunks ?? 1;
    check(reader.chunkIndexes.length >= minChunks,
      `${name}: at least ${minChunks} chunks indexed (${reader.chunkIndexes.length})`);
    for (const ci of reader.chunkIndexes) {
      check(ci.compression === info.compression, `${name}: chunk compression "${ci.compression}"`);
    }
    check(reader.schemasById.size === 3, `${name}: 3 schemas (got ${reader.schemasById.size})`);
    check(reader.channelsById.size === 3, `${name}: 3 channels (got ${reader.channelsById.size})`);
    const stats = reader.statistics;
    check(stats != undefined && stats.messageCount === BigInt(3 * frames),
      `${name}: statistics.messageCount ${stats?.messageCount} == ${3 * frames}`);
    check(stats != undefined && stats.chunkCount === reader.chunkIndexes.length, `${name}: statistics.chunkCount`);

    const decoders = new Map();
    for (const channel of reader.channelsById.values()) {
      const schema = reader.schemasById.get(channel.schemaId);
      const topic = expectedTopics[channel.topic];
      check(topic != undefined, `${name}: channel topic ${channel.topic} is one written`);
      check(channel.messageEncoding === "cdr", `${name}: ${channel.topic} message encoding cdr`);
      check(channel.metadata.get("topic") === channel.topic, `${name}: ${channel.topic} metadata topic`);
      check(channel.metadata.get("type") === topic?.type, `${name}: ${channel.topic} metadata type`);
      check(channel.metadata.get("reliability") === "RELIABLE", `${name}: ${channel.topic} metadata QoS`);
      check(schema?.encoding === "omgidl", `${name}: ${channel.topic} schema encoding omgidl`);
      check(schema?.name === topic?.type, `${name}: ${channel.topic} schema name ${schema?.name}`);
      check(stats?.channelMessageCounts.get(channel.id) === BigInt(frames), `${name}: ${channel.topic} message count`);
      const idl = new TextDecoder().decode(schema.data);
      decoders.set(channel.id, new MessageReader(schema.name, parseIDL(idl)));
    }

    const counts = new Map();
    let lastLogTime = -1n;
    let inOrder = true;
    let decoded = 0;
    for await (const message of reader.readMessages()) {
      const channel = reader.channelsById.get(message.channelId);
      if (message.logTime < lastLogTime) inOrder = false;
      lastLogTime = message.logTime;
      const problems = [];
      // The payload starts with the CDR encapsulation header: 00 01 = CDR little-endian.
      if (message.data[0] !== 0x00 || message.data[1] !== 0x01) problems.push("encapsulation is not CDR_LE");
      const value = decoders.get(message.channelId).readMessage(message.data);
      const expected = expectedTopics[channel.topic].messages[message.sequence];
      matches(expected, value, `${channel.topic}#${message.sequence}`, problems);
      check(problems.length === 0, `${name}: ${channel.topic} message ${message.sequence} decodes as written: ${problems.join("; ")}`);
      counts.set(channel.topic, (counts.get(channel.topic) ?? 0) + 1);
      decoded++;
    }
    check(inOrder, `${name}: messages come in log-time order`);
    check(decoded === 3 * frames, `${name}: read ${decoded} of ${3 * frames} messages`);
    for (const topic of Object.keys(expectedTopics)) {
      check(counts.get(topic) === frames, `${name}: ${topic} has ${counts.get(topic)} of ${frames} messages`);
    }

    // Seeking: one topic in a time range, served from the chunk and message indexes.
    const first = stats.messageStartTime;
    const period = 33333333n;
    let ranged = 0;
    for await (const message of reader.readMessages({
      topics: ["uavmot/tracks"],
      startTime: first + 2n * period,
      endTime: first + 5n * period,
    })) {
      check(reader.channelsById.get(message.channelId).topic === "uavmot/tracks", `${name}: topic filter`);
      ranged++;
    }
    check(ranged === 3, `${name}: 3 track lists in the time range (got ${ranged})`);

    // --- Streaming reader: the whole file record by record, CRCs validated.
    const stream = new McapStreamReader({ decompressHandlers, validateCrcs: true });
    stream.append(new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.byteLength));
    let streamed = 0;
    let sawFooter = false;
    let record;
    while ((record = stream.nextRecord())) {
      if (record.type === "Message") streamed++;
      if (record.type === "Footer") sawFooter = true;
    }
    check(stream.done(), `${name}: stream reader reached the end`);
    check(sawFooter, `${name}: stream reader saw the footer`);
    check(streamed === 3 * frames, `${name}: stream reader saw ${streamed} of ${3 * frames} messages`);
    console.log(`${name}: ${decoded} messages read and decoded, ${reader.chunkIndexes.length} chunks (${info.compression || "none"})`);
  } catch (error) {
    check(false, `${name}: ${error.stack ?? error}`);
  } finally {
    await handle.close();
  }
}

try {
  await checkInterop(dir, mcapInfo, check);
} catch (error) {
  check(false, `interop: ${error.stack ?? error}`);
}

console.log(`${passed} passed, ${failed} failed`);
process.exit(failed === 0 ? 0 : 1);
