// Plays an mp4 in headless Chromium (Debian's /usr/bin/chromium through playwright-core: no
// browser download) from a page served on localhost: waits for `loadeddata`, seeks to the middle,
// draws the decoded frame into a canvas and reads its pixels back. Fails unless the frame has the
// video's size (and the expected one, when given) and is not blank (grey-level standard deviation
// above 8). Optionally saves the page's canvas as a PNG.
//   node play.mjs VIDEO.mp4 [--size WxH] [--png OUT.png]
import { createServer } from 'node:http';
import { mkdtempSync, readFileSync, rmSync, statSync, createReadStream, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { chromium } from 'playwright-core';

const [videoPath, ...rest] = process.argv.slice(2);
const option = (name) => (rest.indexOf(name) >= 0 ? rest[rest.indexOf(name) + 1] : undefined);
const expectedSize = option('--size');
const pngPath = option('--png');

const page = `<!doctype html><html><body>
<video id="v" src="/video.mp4" muted playsinline preload="auto"></video>
<canvas id="c"></canvas>
<script>
window.result = new Promise((resolve) => {
  const v = document.getElementById('v');
  v.addEventListener('error', () => resolve({ error: 'video error ' + (v.error && v.error.code) + ': ' + (v.error && v.error.message) }));
  v.addEventListener('loadeddata', () => {
    v.addEventListener('seeked', () => {
      const c = document.getElementById('c');
      c.width = v.videoWidth;
      c.height = v.videoHeight;
      const g = c.getContext('2d', { willReadFrequently: true });
      g.drawImage(v, 0, 0);
      const d = g.getImageData(0, 0, c.width, c.height).data;
      let sum = 0, sum2 = 0;
      const n = c.width * c.height;
      for (let i = 0; i < d.length; i += 4) {
        const y = 0.299 * d[i] + 0.587 * d[i + 1] + 0.114 * d[i + 2];
        sum += y;
        sum2 += y * y;
      }
      const mean = sum / n;
      resolve({ width: v.videoWidth, height: v.videoHeight, duration: v.duration, time: v.currentTime,
                mean, std: Math.sqrt(Math.max(0, sum2 / n - mean * mean)), png: c.toDataURL('image/png') });
    }, { once: true });
    v.currentTime = v.duration / 2;
  }, { once: true });
});
</script></body></html>`;

// Byte ranges: Chromium's media stack reads mp4s in ranges and seeks with them.
const server = createServer((req, res) => {
  if (req.url === '/') {
    res.writeHead(200, { 'Content-Type': 'text/html' });
    return res.end(page);
  }
  if (req.url !== '/video.mp4') {
    res.writeHead(404);
    return res.end();
  }
  const size = statSync(videoPath).size;
  const range = /bytes=(\d*)-(\d*)/.exec(req.headers.range ?? '');
  if (!range) {
    res.writeHead(200, { 'Content-Type': 'video/mp4', 'Content-Length': size, 'Accept-Ranges': 'bytes' });
    return createReadStream(videoPath).pipe(res);
  }
  const start = range[1] ? Number(range[1]) : 0;
  const end = range[2] ? Math.min(Number(range[2]), size - 1) : size - 1;
  res.writeHead(206, { 'Content-Type': 'video/mp4', 'Content-Length': end - start + 1, 'Accept-Ranges': 'bytes',
                       'Content-Range': `bytes ${start}-${end}/${size}` });
  createReadStream(videoPath, { start, end }).pipe(res);
});
await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
const url = `http://127.0.0.1:${server.address().port}/`;

const profile = mkdtempSync(join(tmpdir(), 'uavmot-chromium-'));
let browser;
let failed = false;
try {
  // A fresh profile each run (playwright passes it as --user-data-dir).
  browser = await chromium.launchPersistentContext(profile, {
    executablePath: '/usr/bin/chromium',
    headless: true,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
           '--disable-component-update', '--disable-sync'],
  });
  const tab = browser.pages()[0] ?? (await browser.newPage());
  await tab.goto(url);
  let timer;
  const r = await Promise.race([tab.evaluate(() => window.result),
                                new Promise((resolve) => { timer = setTimeout(() => resolve({ error: 'no decoded frame within 60 s' }), 60000); })]);
  clearTimeout(timer);
  console.log(`chromium ${browser.browser()?.version() ?? ''}: ${JSON.stringify({ ...r, png: r.png ? `${r.png.length} chars` : undefined })}`);
  const fail = (message) => { console.error(`FAIL ${message}`); failed = true; };
  if (r.error) fail(r.error);
  else {
    if (expectedSize && `${r.width}x${r.height}` !== expectedSize) fail(`frame is ${r.width}x${r.height}, expected ${expectedSize}`);
    if (!(r.std > 8)) fail(`frame looks blank: grey mean ${r.mean.toFixed(1)}, std ${r.std.toFixed(2)}`);
    if (pngPath) writeFileSync(pngPath, Buffer.from(r.png.split(',')[1], 'base64'));
  }
} finally {
  if (browser) await browser.close();
  server.close();
  rmSync(profile, { recursive: true, force: true });
}
if (failed) process.exit(1);
console.log('playback ok');
