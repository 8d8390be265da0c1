// A small Foxglove-compatible image viewer for headless Chromium (bundled by esbuild at test
// time): connects to `uavmot foxglove` with @foxglove/ws-protocol's FoxgloveClient (the browser's
// WebSocket), decodes with @foxglove/omgidl-serialization, and draws like Foxglove's Image panel:
// the CompressedImage, then every ImageAnnotations of the same timestamp over it (polygons,
// points, line lists, text with background). No Foxglove app installs from npm, so this page
// stands in for it with the same client libraries.

import { FoxgloveClient } from "@foxglove/ws-protocol";
import { parseIDL } from "@foxglove/omgidl-parser";
import { MessageReader } from "@foxglove/omgidl-serialization";

const url = new URLSearchParams(location.search).get("ws");
const frames = new Map();  // "sec.nsec" -> {image, annotations: {topic: ImageAnnotations}}
const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
const channels = new Map();
window.viewer = { messages: 0, errors: [] };

const key = (t) => `${t.sec}.${String(t.nsec).padStart(9, "0")}`;
const entry = (k) => {
  if (!frames.has(k)) frames.set(k, { annotations: {} });
  return frames.get(k);
};

client.on("advertise", (advertised) => {
  for (const c of advertised) {
    if (!c.topic.startsWith("uavmot/foxglove/")) continue;
    const reader = new MessageReader(c.schemaName, parseIDL(c.schema));
    channels.set(client.subscribe(c.id), { topic: c.topic, schemaName: c.schemaName, reader });
  }
  window.viewer.subscribed = channels.size;
});
client.on("message", ({ subscriptionId, data }) => {
  const c = channels.get(subscriptionId);
  try {
    const value = c.reader.readMessage(new Uint8Array(data.buffer, data.byteOffset, data.byteLength));
    window.viewer.messages++;
    if (c.schemaName === "foxglove::CompressedImage") {
      entry(key(value.timestamp)).image = value;
    } else {
      const first = value.points[0] ?? value.texts[0] ?? value.circles[0];
      if (first) entry(key(first.timestamp)).annotations[c.topic] = value;
    }
  } catch (e) {
    window.viewer.errors.push(`${c.topic}: ${e.message}`);
  }
});

const css = (c) => `rgba(${Math.round(c.r * 255)}, ${Math.round(c.g * 255)}, ${Math.round(c.b * 255)}, ${c.a})`;

function drawAnnotations(g, a) {
  for (const p of a.points) {
    g.strokeStyle = css(p.outline_color);
    g.fillStyle = css(p.outline_color);
    g.lineWidth = p.thickness;
    if (p.type === 1) {  // POINTS
      for (const q of p.points) {
        g.beginPath();
        g.arc(q.x, q.y, p.thickness / 2, 0, 2 * Math.PI);
        g.fill();
      }
    } else if (p.type === 4) {  // LINE_LIST
      g.beginPath();
      for (let i = 0; i + 1 < p.points.length; i += 2) {
        g.moveTo(p.points[i].x, p.points[i].y);
        g.lineTo(p.points[i + 1].x, p.points[i + 1].y);
      }
      g.stroke();
    } else if (p.type === 2 || p.type === 3) {  // LINE_LOOP, LINE_STRIP
      g.beginPath();
      p.points.forEach((q, i) => (i ? g.lineTo(q.x, q.y) : g.moveTo(q.x, q.y)));
      if (p.type === 2) g.closePath();
      if (p.fill_color.a > 0) {
        g.fillStyle = css(p.fill_color);
        g.fill();
      }
      g.stroke();
    }
  }
  for (const t of a.texts) {
    g.font = `${t.font_size}px sans-serif`;
    const w = g.measureText(t.text).width;
    g.fillStyle = css(t.background_color);
    g.fillRect(t.position.x, t.position.y - t.font_size, w + 2, t.font_size + 2);
    g.fillStyle = css(t.text_color);
    g.fillText(t.text, t.position.x + 1, t.position.y);
  }
}

// Draws the newest frame whose image and track labels both arrived; returns what it drew.
window.renderBest = async () => {
  const ready = [...frames.entries()].filter(([, f]) => f.image && f.annotations["uavmot/foxglove/tracks"]?.texts.length);
  if (!ready.length) return { error: `no frame with image and labelled tracks (${frames.size} timestamps)` };
  ready.sort(([a], [b]) => (a < b ? -1 : 1));
  const [stamp, f] = ready[ready.length - 1];
  const bitmap = await createImageBitmap(new Blob([f.image.data], { type: `image/${f.image.format}` }));
  const canvas = document.getElementById("c");
  canvas.width = bitmap.width;
  canvas.height = bitmap.height;
  const g = canvas.getContext("2d", { willReadFrequently: true });
  g.drawImage(bitmap, 0, 0);
  for (const topic of ["uavmot/foxglove/features", "uavmot/foxglove/regions", "uavmot/foxglove/tracks"]) {
    if (f.annotations[topic]) drawAnnotations(g, f.annotations[topic]);
  }
  // Pure track green (uavmot-view's colour) appears only where annotations were drawn.
  const d = g.getImageData(0, 0, canvas.width, canvas.height).data;
  let green = 0;
  for (let i = 0; i < d.length; i += 4) if (d[i] < 60 && d[i + 1] > 200 && d[i + 2] < 60) green++;
  return { stamp, width: canvas.width, height: canvas.height, green, frames: ready.length,
           layers: Object.keys(f.annotations), labels: f.annotations["uavmot/foxglove/tracks"].texts.length };
};
