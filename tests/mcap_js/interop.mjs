// The other direction: files written by the official TypeScript writer (@mcap/core McapWriter)
// are read by uavmot's C++ reader (mcap_info --json --messages), message for message.
// Covers what uavmot's own writer never produces: schemas and channels inside chunks, messages
// outside chunks (no chunk index), zstd from another encoder.

import { execFileSync } from "node:child_process";
import { writeFile } from "node:fs/promises";
import path from "node:path";

import { McapWriter } from "@mcap/core";
import * as zstd from "@foxglove/wasm-zstd";

function fnv1a64(bytes) {
  let hash = 14695981039346656037n;
  for (const b of bytes) {
    hash ^= BigInt(b);
    hash = (hash * 1099511628211n) & 0xffffffffffffffffn;
  }
  return hash;
}

async function writeOfficial(file, options) {
  const parts = [];
  let position = 0n;
  const writable = {
    position: () => position,
    write: async (buffer) => {
      parts.push(buffer.slice());
      position += BigInt(buffer.byteLength);
    },
  };
  const writer = new McapWriter({ writable, ...options });
  await writer.start({ profile: "", library: "mcap-ts interop check" });
  const schema = await writer.registerSchema({
    name: "demo::Point",
    encoding: "omgidl",
    data: new TextEncoder().encode("module demo { struct Point { double x; double y; }; };"),
  });
  const channels = [
    await writer.registerChannel({ topic: "demo/a", messageEncoding: "cdr", schemaId: schema, metadata: new Map([["k", "v"]]) }),
    await writer.registerChannel({ topic: "demo/b", messageEncoding: "cdr", schemaId: schema, metadata: new Map() }),
  ];
  const written = [];
  for (let i = 0; i < 300; i++) {
    const data = new Uint8Array(20 + ((i * 13) % 200));
    for (let k = 0; k < data.length; k++) data[k] = (i * 7 + k * 3) & 0xff;
    // Log times jitter so chunks overlap: the reader must still merge them in order.
    const logTime = 1000000n + BigInt(i) * 1000n + BigInt((i * 7919) % 3000);
    const message = { channelId: channels[i % 2], sequence: i, logTime, publishTime: logTime - 5n, data };
    await writer.addMessage(message);
    written.push({ topic: i % 2 ? "demo/b" : "demo/a", ...message });
  }
  await writer.end();
  await writeFile(file, Buffer.concat(parts));
  return written;
}

export async function checkInterop(dir, mcapInfo, check) {
  await zstd.isLoaded;
  const variants = {
    "official_chunked_none.mcap": { chunkSize: 2048 },
    "official_chunked_zstd.mcap": {
      chunkSize: 2048,
      compressChunk: (data) => ({ compression: "zstd", compressedData: zstd.compress(data, 3) }),
    },
    "official_unchunked.mcap": { useChunks: false },
  };
  for (const [name, options] of Object.entries(variants)) {
    const file = path.join(dir, name);
    const written = await writeOfficial(file, options);
    let info;
    try {
      info = JSON.parse(execFileSync(mcapInfo, ["--json", "--messages", file], { encoding: "utf8" }));
    } catch (error) {
      check(false, `${name}: mcap_info failed: ${error.stdout ?? ""}${error.stderr ?? error}`);
      continue;
    }
    check(info.damage.length === 0, `${name}: C++ reader finds no damage (${info.damage.join("; ")})`);
    check(info.messages === written.length && info.messages_read === written.length,
      `${name}: C++ reader counts ${info.messages} / reads ${info.messages_read} of ${written.length}`);
    check(info.channels.length === 2 && info.channels[0].metadata.k === "v", `${name}: channels and metadata`);
    check(info.schemas.length === 1 && info.schemas[0].name === "demo::Point", `${name}: schema`);
    const expected = [...written].sort((a, b) => (a.logTime < b.logTime ? -1 : a.logTime > b.logTime ? 1 : 0));
    let same = info.message_list.length === expected.length;
    for (let i = 0; same && i < expected.length; i++) {
      const got = info.message_list[i];
      const want = expected[i];
      same = got.topic === want.topic && got.sequence === want.sequence && got.log_time === String(want.logTime) &&
        got.publish_time === String(want.publishTime) && got.size === want.data.length &&
        got.fnv1a64 === String(fnv1a64(want.data));
      if (!same) console.error(`${name}: message ${i}: got ${JSON.stringify(got)}, want seq ${want.sequence}`);
    }
    check(same, `${name}: C++ reader returns every message, bytes intact, in log-time order`);
    console.log(`${name}: read by the C++ reader (${info.indexed ? "indexed" : "scanned"}), ${info.messages_read} messages`);
  }
}
