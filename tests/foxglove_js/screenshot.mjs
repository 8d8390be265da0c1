// Screenshots viewer_page.js (bundled with esbuild) in headless Chromium (Debian's /usr/bin/chromium
// through playwright-core) while it is connected to `uavmot foxglove`: the image with the chain's
// annotations over it, as Foxglove's Image panel shows them. Fails unless the page subscribed,
// decoded without errors and drew a frame with labelled tracks (green pixels of the track colour).
//   node screenshot.mjs WS_URL --ready FILE --done FILE --png OUT.png [--timeout S]
import { createServer } from "node:http";
import { existsSync, mkdtempSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";

import { build } from "esbuild";
import { chromium } from "playwright-core";

const [wsUrl, ...rest] = process.argv.slice(2);
const option = (name, fallback) => (rest.includes(name) ? rest[rest.indexOf(name) + 1] : fallback);
const readyFile = option("--ready");
const doneFile = option("--done");
const pngPath = option("--png");
const timeoutS = Number(option("--timeout", "180"));
const here = dirname(fileURLToPath(import.meta.url));

const bundle = await build({ entryPoints: [join(here, "viewer_page.js")], bundle: true, write: false, format: "iife",
                             platform: "browser", logLevel: "error" });
const script = bundle.outputFiles[0].text;
const html = `<!doctype html><html><body style="margin:0;background:#222"><canvas id="c"></canvas>
<script src="/viewer.js"></script></body></html>`;
const server = createServer((req, res) => {
  if (req.url.startsWith("/viewer.js")) {
    res.writeHead(200, { "Content-Type": "text/javascript" });
    return res.end(script);
  }
  res.writeHead(200, { "Content-Type": "text/html" });
  res.end(html);
});
await new Promise((resolve) => server.listen(0, "127.0.0.1", resolve));

const profile = mkdtempSync(join(tmpdir(), "uavmot-chromium-"));
let browser;
let failed = false;
const fail = (message) => {
  console.error(`FAIL ${message}`);
  failed = true;
};
try {
  browser = await chromium.launchPersistentContext(profile, {
    executablePath: "/usr/bin/chromium",
    headless: true,
    viewport: { width: 1100, height: 800 },
    args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
           "--disable-background-networking", "--disable-component-update", "--disable-sync"],
  });
  const tab = browser.pages()[0] ?? (await browser.newPage());
  tab.on("pageerror", (e) => fail(`page error: ${e.message}`));
  await tab.goto(`http://127.0.0.1:${server.address().port}/?ws=${encodeURIComponent(wsUrl)}`);
  await tab.waitForFunction(() => window.viewer?.subscribed >= 4, null, { timeout: 30000 });
  writeFileSync(readyFile, "subscribed\n");
  const start = Date.now();
  while (!existsSync(doneFile) && Date.now() - start < timeoutS * 1000) await new Promise((r) => setTimeout(r, 200));
  await new Promise((r) => setTimeout(r, 2000));
  const viewer = await tab.evaluate(() => window.viewer);
  const drawn = await tab.evaluate(() => window.renderBest());
  console.log(`chromium ${browser.browser()?.version() ?? ""}: ${viewer.messages} messages; drew ${JSON.stringify(drawn)}`);
  if (viewer.errors.length) fail(`decode errors: ${viewer.errors.slice(0, 3).join("; ")}`);
  if (drawn.error) fail(drawn.error);
  else {
    if (!(drawn.green > 200)) fail(`only ${drawn.green} track-green pixels: annotations not drawn`);
    if (!drawn.layers.includes("uavmot/foxglove/regions")) fail("no region annotations for the drawn frame");
    const canvas = await tab.$("#c");
    writeFileSync(pngPath, await canvas.screenshot({ type: "png" }));
    console.log(`wrote ${pngPath}`);
  }
} catch (e) {
  fail(e.stack ?? String(e));
} finally {
  if (browser) await browser.close();
  server.close();
  rmSync(profile, { recursive: true, force: true });
}
process.exit(failed ? 1 : 0);
