// Validates tracks.geojson with two GeoJSON validators from npm: @mapbox/geojsonhint (no errors,
// no warnings) and geojson-validation (its FeatureCollection check); then the properties uavmot
// promises, and that
// each LineString position lies inside the footprint polygon of the frame it came from.
// When footprints.json lists only frames (no per-track frame lists: the output of `uavmot process`,
// tests/geo_js/process_run.sh), each position must lie inside the union of the footprints of the
// frames its track spans (first_frame .. last_frame).
//   node validate.mjs tracks.geojson footprints.json [--min-features N]
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';

const require = createRequire(import.meta.url);
const geojsonhint = require('@mapbox/geojsonhint');
const gjv = require('geojson-validation');

const [tracksPath, footprintsPath, ...rest] = process.argv.slice(2);
const minFeatures = rest[0] === '--min-features' ? Number(rest[1]) : 0;
const text = readFileSync(tracksPath, 'utf8');
const footprints = JSON.parse(readFileSync(footprintsPath, 'utf8'));
const failures = [];
const fail = (message) => failures.push(message);

const hints = geojsonhint.hint(text);
for (const h of hints) fail(`geojsonhint: ${h.message}${h.line ? ` (line ${h.line})` : ''}`);

const doc = JSON.parse(text);
const gjvErrors = gjv.valid(doc, true);
for (const e of Array.isArray(gjvErrors) ? gjvErrors : []) fail(`geojson-validation: ${e}`);
if (!gjv.isFeatureCollection(doc)) fail('geojson-validation: not a valid FeatureCollection');

// Ray casting; ring is [[lon, lat], ...] (not closed).
function inside([x, y], ring) {
  let odd = false;
  for (let i = 0, j = ring.length - 1; i < ring.length; j = i++) {
    const [xi, yi] = ring[i];
    const [xj, yj] = ring[j];
    if ((yi > y) !== (yj > y) && x < ((xj - xi) * (y - yi)) / (yj - yi) + xi) odd = !odd;
  }
  return odd;
}

if (doc.type !== 'FeatureCollection') fail('not a FeatureCollection');
let positions = 0;
for (const feature of doc.features ?? []) {
  const p = feature.properties ?? {};
  const name = `track ${p.id}`;
  for (const key of ['id', 'first_time_s', 'last_time_s', 'first_frame', 'last_frame', 'mean_speed_mps']) {
    if (typeof p[key] !== 'number' || !Number.isFinite(p[key])) fail(`${name}: property ${key} missing or not a number`);
  }
  if (feature.geometry?.type !== 'LineString') fail(`${name}: geometry is not a LineString`);
  if (!(p.last_time_s >= p.first_time_s) || !(p.last_frame >= p.first_frame)) fail(`${name}: times or frames out of order`);
  if (!(p.mean_speed_mps >= 0)) fail(`${name}: negative speed`);
  const coordinates = feature.geometry?.coordinates ?? [];
  if (!footprints.tracks) {
    const rings = [];
    for (let k = p.first_frame; k <= p.last_frame; k++) if (footprints.frames[String(k)]) rings.push(footprints.frames[String(k)]);
    if (rings.length === 0) fail(`${name}: no footprint for frames ${p.first_frame}..${p.last_frame}`);
    coordinates.forEach((position, i) => {
      positions++;
      const [lon, lat] = position;
      if (!(Math.abs(lon) <= 180 && Math.abs(lat) <= 90)) fail(`${name}: position ${i} not [lon, lat]: ${position}`);
      if (!rings.some((ring) => inside(position, ring))) fail(`${name}: position ${i} [${position}] outside frames ${p.first_frame}..${p.last_frame}' footprints`);
    });
    continue;
  }
  const frames = footprints.tracks[String(p.id)] ?? [];
  if (frames.length !== coordinates.length) fail(`${name}: ${coordinates.length} positions but ${frames.length} frames`);
  if (frames[0] !== p.first_frame || frames[frames.length - 1] !== p.last_frame) fail(`${name}: first/last frame differ from its points`);
  coordinates.forEach((position, i) => {
    positions++;
    const [lon, lat] = position;
    if (!(Math.abs(lon) <= 180 && Math.abs(lat) <= 90)) fail(`${name}: position ${i} not [lon, lat]: ${position}`);
    const ring = footprints.frames[String(frames[i])];
    if (!ring) fail(`${name}: no footprint for frame ${frames[i]}`);
    else if (!inside(position, ring)) fail(`${name}: position ${i} [${position}] outside frame ${frames[i]}'s footprint`);
  });
}

if ((doc.features ?? []).length < minFeatures) fail(`${(doc.features ?? []).length} features, at least ${minFeatures} expected`);

if (failures.length > 0) {
  for (const f of failures) console.error(`FAIL ${f}`);
  console.error(`${failures.length} failed`);
  process.exit(1);
}
console.log(`geojson ok: ${doc.features.length} features, ${positions} positions inside their footprints, geojsonhint and geojson-validation clean`);
