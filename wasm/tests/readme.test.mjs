// The README's "In the browser" example, run under node: tests/readme_snippets.rs
// checks that the README block is made of these lines, in order. The page's
// fetch() is stood in for by one that reads the build directory.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import { Aaglsd, rgbaToGray } from '../js/aaglsd.mjs';

const root = fileURLToPath(new URL('../../', import.meta.url));
const targetDir = path.resolve(root, process.env.CARGO_TARGET_DIR ?? 'target');
const wasmPath =
  process.env.AAGLSD_WASM ??
  path.join(targetDir, 'wasm32-unknown-unknown', 'release', 'aaglsd_wasm.wasm');

test('README: In the browser', async () => {
  const fetch = async () => new Response(readFileSync(wasmPath));
  const [width, height] = [64, 48];
  const rgba = new Uint8Array(4 * width * height).fill(200); // a canvas's getImageData().data
  for (let y = 12; y < 36; y++) rgba.fill(40, 4 * (y * width + 16), 4 * (y * width + 48));
  const lines = [];
  // --- README: In the browser ---
  const lsd = await Aaglsd.instantiate(await fetch('aaglsd_wasm.wasm'));
  const gray = rgbaToGray(rgba, width, height); // BT.601, as the Python package
  const config = lsd.profile('paper'); // every Config field, by name
  config.min_length_px = 20;
  const r = lsd.detect(gray, width, height, config); // r.segments: x0 y0 x1 y1, r.scores
  lines.push(`${r.count} segments in ${r.ms.toFixed(2)} ms`);
  // --- end ---
  // All four sides (32 and 24 px: the paper profile's symmetric maxima keep
  // the short ones longer than 20 px); each scored.
  assert.equal(r.count, 4, 'the four sides of the rectangle');
  assert.equal(r.segments.length, 16);
  assert.equal(r.scores.length, 4);
  assert.ok(r.scores.every((s) => s > 0));
  assert.match(lines[0], /^4 segments in \d+\.\d\d ms$/);
});
