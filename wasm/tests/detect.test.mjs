// Node test of the aaglsd wasm module (no npm packages): `node --test wasm/tests/`.
//
// Needs the module (cargo build -p aaglsd-wasm --release --target
// wasm32-unknown-unknown) and, for the comparison with the host, the files
// written by `cargo run -p aaglsd-wasm --release --example wasm_expected -- DIR`.
// wasm/tests/run.sh does all three. Paths: AAGLSD_WASM (the .wasm) and
// AAGLSD_WASM_EXPECTED (DIR), defaulting to $CARGO_TARGET_DIR or target/.
// run.sh runs this file once per module: AAGLSD_WASM_KIND (plain or simd)
// says which AAGLSD_WASM is, and AAGLSD_WASM_MODULES is the folder of both
// (wasm/build.sh), for Aaglsd.load.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import { Aaglsd, AaglsdError, FIELDS, SEGMENT_BYTES, rgbaToGray } from '../js/aaglsd.mjs';

const root = fileURLToPath(new URL('../../', import.meta.url));
const targetDir = path.resolve(root, process.env.CARGO_TARGET_DIR ?? 'target');
const wasmPath =
  process.env.AAGLSD_WASM ??
  path.join(targetDir, 'wasm32-unknown-unknown', 'release', 'aaglsd_wasm.wasm');
const expectedDir = process.env.AAGLSD_WASM_EXPECTED ?? path.join(targetDir, 'wasm-test');
const expected = () => JSON.parse(readFileSync(path.join(expectedDir, 'expected.json'), 'utf8'));

const load = () => Aaglsd.instantiate(readFileSync(wasmPath));
const kind = process.env.AAGLSD_WASM_KIND;
const modulesDir = process.env.AAGLSD_WASM_MODULES;

/** The f32 bit patterns of a detection, one [x0, y0, x1, y1, score] per segment. */
function bits(r) {
  assert.equal(r.segments.length, 4 * r.count);
  assert.equal(r.scores.length, r.count);
  const u = new Uint32Array(r.segments.buffer, r.segments.byteOffset, r.segments.length);
  const s = new Uint32Array(r.scores.buffer, r.scores.byteOffset, r.scores.length);
  return Array.from({ length: r.count }, (_, i) => [...u.subarray(4 * i, 4 * i + 4), s[i]]);
}

/** The pixel at (x, y) rounded to the nearest, of a packed gray image. */
function pixelAt({ width, pixels }, x, y) {
  return pixels[Math.round(y) * width + Math.round(x)];
}

/** Reads a binary PGM as written by the wasm_expected example. */
function readPgm(file) {
  const bytes = readFileSync(file);
  const m = /^P5\s+(\d+)\s+(\d+)\s+255\s/.exec(bytes.subarray(0, 64).toString('latin1'));
  assert.ok(m, `${file}: not an 8-bit P5 PGM`);
  const [width, height] = [Number(m[1]), Number(m[2])];
  return { width, height, pixels: bytes.subarray(m[0].length, m[0].length + width * height) };
}

/** The README's example: a dark 32 x 24 rectangle on a 64 x 48 light image. */
function rectangle() {
  const [width, height] = [64, 48];
  const pixels = new Uint8Array(width * height).fill(200);
  for (let y = 12; y < 36; y++) pixels.fill(40, y * width + 16, y * width + 48);
  return { width, height, pixels };
}

/** wasm_expected's synthetic_pixel: 250-pixel checks of 60 and 190, textured. */
function synthetic(width, height) {
  const pixels = new Uint8Array(width * height);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const check = ((Math.floor(x / 250) + Math.floor(y / 250)) % 2 === 0) ? 60 : 190;
      pixels[y * width + x] = check + ((x * 3 + y * 5) % 7);
    }
  }
  return pixels;
}

function configOf(lsd, run) {
  return { ...lsd.profile(run.profile), ...run.set };
}

test('exports and names', async () => {
  const lsd = await load();
  const e = lsd.wasm;
  for (const f of ['alloc', 'release', 'config_size', 'config_field_offset', 'config_profile',
    'config_validate', 'workspace_size', 'default_max_segments', 'segment_size', 'simd128',
    'detect', 'status_name', 'config_field_name']) {
    assert.equal(typeof e[f], 'function', f);
  }
  assert.equal(e.segment_size(), SEGMENT_BYTES);
  assert.equal(SEGMENT_BYTES, 20, 'x0 y0 x1 y1 score');
  // A module of another layout (the 16-byte segments of old builds) is refused.
  assert.throws(() => new Aaglsd({ ...e, segment_size: () => 16 }), /16-byte segments/);
  assert.ok(e.memory instanceof WebAssembly.Memory);
  assert.equal(lsd.configSize, 76);
  assert.equal(lsd.statusNames[0], 'ok');
  assert.equal(lsd.statusNames[7], 'invalid_config');
  assert.equal(lsd.statusNames[13], 'out_of_bounds');
  assert.equal(lsd.statusNames[14], 'out_of_memory');
  assert.equal(lsd.fieldNames[6], 'min_length_px');
  assert.equal(lsd.fieldNames[14], 'max_link_pixels');
  assert.equal(lsd.fieldNames[16], 'work_per_mille');
  assert.equal(e.config_field_offset(FIELDS.length), -11, 'invalid_argument');
});

test('the module says whether it has simd128; Aaglsd.load picks by the engine', async () => {
  const lsd = await load();
  assert.equal(typeof lsd.simd, 'boolean');
  if (kind) assert.equal(lsd.simd, kind === 'simd', `AAGLSD_WASM_KIND=${kind}`);
  // Node >= 20 has simd128.
  assert.equal(Aaglsd.simdSupported(), true);
  if (!modulesDir) return;
  const plainPath = path.join(modulesDir, 'aaglsd_wasm.wasm');
  const simdPath = path.join(modulesDir, 'aaglsd_wasm_simd.wasm');
  const fetched = [];
  const source = (file) => async () => {
    fetched.push(path.basename(file));
    return new Response(readFileSync(file));
  };
  const sources = { plain: source(plainPath), simd: source(simdPath) };
  const picked = await Aaglsd.load(sources);
  assert.equal(picked.simd, true);
  assert.deepEqual(fetched, ['aaglsd_wasm_simd.wasm'], 'only the chosen module is fetched');
  assert.equal((await Aaglsd.load(sources, { simd: false })).simd, false);
  assert.equal((await Aaglsd.load({ plain: readFileSync(plainPath) })).simd, false, 'no simd given');
  // An engine without simd128 (the probe does not validate) gets the plain module.
  const validate = WebAssembly.validate;
  WebAssembly.validate = () => false;
  try {
    assert.equal(Aaglsd.simdSupported(), false);
    assert.equal((await Aaglsd.load(sources)).simd, false);
  } finally {
    WebAssembly.validate = validate;
  }
  // The same segments either way.
  const { width, height, pixels } = rectangle();
  const [a, b] = [picked, await Aaglsd.load(sources, { simd: false })]
    .map((m) => bits(m.detect(pixels, width, height)));
  assert.deepEqual(a, b);
});

test('profiles read back field by field', async () => {
  const lsd = await load();
  const paper = lsd.profile('paper');
  assert.equal(paper.min_length_px, 9);
  assert.equal(paper.merge, 1);
  assert.equal(paper.min_groups, 3);
  assert.equal(paper.max_link_pixels, 1024);
  assert.equal(paper.candidates_per_mille, 100);
  assert.equal(paper.work_per_mille, 2000);
  assert.ok(Math.abs(paper.magnitude_threshold - 5.22) < 1e-6);
  const official = lsd.profile(1);
  assert.deepEqual({ ...official, min_length_px: 9, min_groups: 3, anchor_density: 0.5,
    aligned_density: 0.5, maxima: 1, merge: 1 }, paper);
  assert.deepEqual(lsd.profile('default'), lsd.profile(0));
  assert.deepEqual({ ...official, extend_max_px: 64, maxima: 1, bridge_px: 6, min_score: 150, merge: 1,
    trim: 1, reseed: 3 },
    lsd.profile('default'));
  assert.equal(official.maxima, 0); // Maxima::Strict; 1 is Maxima::Symmetric
  assert.equal(official.reseed, 1); // Reseed::Always; the default's 3 is Reseed::Misfit
  assert.throws(() => lsd.profile(3), (err) => err instanceof AaglsdError &&
    err.statusName === 'invalid_argument');
  assert.equal(lsd.validate(paper), null);
  assert.equal(lsd.validate({ ...paper, min_length_px: -1 }), 'min_length_px');
  assert.equal(lsd.validate({ ...paper, skip_group: 0 }), 'skip_min/skip_regular/skip_group');
  assert.equal(lsd.validate({ ...paper, max_link_pixels: 15 }), 'max_link_pixels');
  assert.equal(lsd.validate({ ...paper, work_per_mille: 0 }), 'work_per_mille');
  assert.equal(lsd.validate({ ...paper, align_tolerance_deg: NaN }), 'align_tolerance_deg');
});

test('the README rectangle has four sides, bright side on the left, scored', async () => {
  const lsd = await load();
  const img = rectangle();
  const { width, height, pixels } = img;
  const r = lsd.detect(pixels, width, height);
  assert.equal(r.count, 4);
  assert.equal(r.summary.segments, 4);
  for (let i = 0; i < 4; i++) {
    const [x0, y0, x1, y1] = r.segments.subarray(4 * i, 4 * i + 4);
    const len = Math.hypot(x1 - x0, y1 - y0);
    assert.ok(len > 15, 'sides of 32 and 24 px');
    // Three pixels to the left of the direction (x right, y down) is the
    // light background, three to the right the dark rectangle.
    const [lx, ly] = [(y1 - y0) / len, -(x1 - x0) / len];
    const [mx, my] = [(x0 + x1) / 2, (y0 + y1) / 2];
    assert.equal(pixelAt(img, mx + 3 * lx, my + 3 * ly), 200, `side ${i}: left is bright`);
    assert.equal(pixelAt(img, mx - 3 * lx, my - 3 * ly), 40, `side ${i}: right is dark`);
    // The contrast of a 160-level step summed over each side's pixels:
    // about 115 a pixel after the blur, a little less where the corners
    // lower the shares of anchors and aligned pixels.
    assert.ok(Number.isInteger(r.scores[i]) && r.scores[i] > 90 * len, `score ${r.scores[i]}`);
  }
  // The inverted image: the same sides, each reversed (their ends may
  // differ at the corners, where the blur's rounding is not symmetric).
  const inv = lsd.detect(pixels.map((v) => 255 - v), width, height);
  assert.equal(inv.count, 4);
  const side = (s, i) => s.subarray(4 * i, 4 * i + 4);
  for (let i = 0; i < 4; i++) {
    const [a0, b0, a1, b1] = side(inv.segments, i);
    const reversed = Array.from({ length: 4 }, (_, j) => side(r.segments, j)).some(
      ([x0, y0, x1, y1]) => Math.hypot((a0 + a1 - x0 - x1) / 2, (b0 + b1 - y0 - y1) / 2) < 1 &&
        (a1 - a0) * (x1 - x0) + (b1 - b0) * (y1 - y0) < 0);
    assert.ok(reversed, `inverted side ${i} is a side reversed`);
  }
});

test('segments equal the host Rust output bit for bit', async () => {
  const lsd = await load();
  const exp = expected();
  const img = readPgm(path.join(expectedDir, 'input.pgm'));
  assert.deepEqual([img.width, img.height], [exp.width, exp.height]);
  assert.equal(exp.runs.length, 4);
  for (const run of exp.runs) {
    const label = `profile ${run.profile} ${JSON.stringify(run.set)}`;
    const r = lsd.detect(img.pixels, img.width, img.height, configOf(lsd, run));
    assert.equal(r.count, run.count, `${label}: count`);
    assert.deepEqual(Object.values(r.summary), run.summary, `${label}: summary`);
    assert.deepEqual(bits(r), run.bits, `${label}: segments`);
  }
  // The same pixels in padded rows (stride > width), and as RGBA gray.
  const stride = img.width + 13;
  const padded = new Uint8Array(stride * (img.height - 1) + img.width).fill(255);
  const rgba = new Uint8Array(4 * img.width * img.height);
  for (let y = 0; y < img.height; y++) {
    const row = img.pixels.subarray(y * img.width, (y + 1) * img.width);
    padded.set(row, y * stride);
    row.forEach((v, x) => rgba.set([v, v, v, 255], 4 * (y * img.width + x)));
  }
  const run = exp.runs[0];
  const r = lsd.detect(padded, img.width, img.height, configOf(lsd, run), { stride });
  assert.deepEqual(bits(r), run.bits, 'padded rows');
  assert.deepEqual(rgbaToGray(rgba, img.width, img.height), new Uint8Array(img.pixels),
    'BT.601 keeps gray pixels');
});

test('a 12-megapixel image works and equals the host', async () => {
  const lsd = await load();
  const run = expected().synthetic;
  assert.equal(run.width * run.height, 12e6);
  const pixels = synthetic(run.width, run.height);
  const r = lsd.detect(pixels, run.width, run.height, configOf(lsd, run));
  // The check borders, each bridged across its junctions and merged into
  // one line: 15 vertical and 11 horizontal.
  assert.equal(r.count, 26, `${r.count} segments`);
  assert.equal(r.count, run.count);
  assert.deepEqual(Object.values(r.summary), run.summary);
  assert.deepEqual(bits(r), run.bits);
  // The image and a workspace of more than a byte per pixel.
  assert.ok(lsd.wasm.memory.buffer.byteLength > 12e6 * 2, 'the memory grew');
});

test('bad sizes and configs get the named status', async () => {
  const lsd = await load();
  const { width, height, pixels } = rectangle();
  const cfg = lsd.profile();
  const status = (fn) => {
    try {
      fn();
    } catch (err) {
      assert.ok(err instanceof AaglsdError, String(err));
      return err.statusName;
    }
    return 'ok';
  };
  assert.equal(status(() => lsd.detect(pixels, 0, height, cfg)), 'zero_dimension');
  assert.equal(status(() => lsd.detect(pixels, width, 0, cfg)), 'zero_dimension');
  assert.equal(status(() => lsd.detect(pixels, 40000, 1, cfg)), 'image_too_large');
  assert.equal(status(() => lsd.detect(pixels, 9000, 9000, cfg)), 'image_too_large');
  assert.equal(status(() => lsd.detect(pixels, width, height + 1, cfg)), 'buffer_too_short');
  assert.equal(status(() => lsd.detect(pixels, width, height, cfg, { stride: width - 1 })),
    'stride_too_small');
  assert.equal(status(() => lsd.detect(pixels, width, height, { ...cfg, min_groups: 0 })),
    'invalid_config');
  assert.equal(status(() => lsd.detect(pixels, width, height, cfg, { maxSegments: 0 })),
    'output_empty');
  assert.equal(status(() => lsd.workspaceSize(0, 5, cfg)), 'zero_dimension');
  assert.equal(lsd.detect(pixels, width, height, cfg, { maxSegments: 2 }).summary.dropped_segments,
    2);
});

test('a short output keeps the highest scores, best first', async () => {
  const lsd = await load();
  const exp = expected();
  const img = readPgm(path.join(expectedDir, 'input.pgm'));
  // The official profile (no merging): the kept are the best of the full run.
  const run = exp.runs.find((x) => x.profile === 1 && Object.keys(x.set).length === 0);
  const full = run.bits;
  const r = lsd.detect(img.pixels, img.width, img.height, configOf(lsd, run), { maxSegments: 5 });
  assert.equal(r.count, 5);
  assert.equal(r.summary.dropped_segments, full.length - 5);
  const kept = bits(r);
  const score = (b) => new Float32Array(new Uint32Array([b[4]]).buffer)[0];
  const keys = new Set(kept.map((b) => b.join(' ')));
  const rest = full.filter((b) => !keys.has(b.join(' ')));
  assert.equal(rest.length, full.length - 5, 'the kept are segments of the full run');
  for (let i = 1; i < 5; i++) assert.ok(score(kept[i - 1]) >= score(kept[i]), 'best first');
  assert.ok(score(kept[4]) >= Math.max(...rest.map(score)), 'none left out scores higher');
});

test('raw exports never trap on bad pointers', async () => {
  const lsd = await load();
  const e = lsd.wasm;
  const { width, height, pixels } = rectangle();
  const end = e.memory.buffer.byteLength;
  const heapBase = e.__heap_base.value;
  const mark = e.alloc(0);
  const cfg = e.alloc(lsd.configSize);
  assert.equal(e.config_profile(0, cfg), 0);
  const wsLen = e.workspace_size(width, height, cfg);
  assert.ok(wsLen > width * height * 3, `${wsLen}`);
  const img = e.alloc(pixels.length);
  const ws = e.alloc(wsLen);
  const out = e.alloc(64 * e.segment_size());
  const sum = e.alloc(9 * 4);
  new Uint8Array(e.memory.buffer, img, pixels.length).set(pixels);
  const good = [img, pixels.length, width, height, width, cfg, ws, wsLen, out, 64, sum];
  assert.equal(e.detect(...good), 4);
  const top = e.memory.buffer.byteLength;
  const cases = [
    ['null image', 0, 0, 'null_pointer'],
    ['null cfg', 5, 0, 'null_pointer'],
    ['null summary', 10, 0, 'null_pointer'],
    ['image in the stack', 0, 16, 'out_of_bounds'],
    ['image below __heap_base', 0, heapBase - 8, 'out_of_bounds'],
    ['image past the end', 0, top - 8, 'out_of_bounds'],
    ['huge image length', 1, 0x7fffffff, 'out_of_bounds'],
    ['negative (huge) address', 0, -16, 'out_of_bounds'],
    ['cfg past the end', 5, top - 4, 'out_of_bounds'],
    ['workspace in the data', 6, 1024, 'out_of_bounds'],
    ['output past the end', 8, top - 512, 'out_of_bounds'],
    ['huge output', 9, 0x40000000, 'out_of_bounds'],
    ['summary past the end', 10, top - 4, 'out_of_bounds'],
    ['misaligned output', 8, out + 2, 'misaligned'],
    ['workspace over the image', 6, img + 8, 'buffers_overlap'],
  ];
  for (const [name, i, v, want] of cases) {
    const args = good.slice();
    args[i] = v;
    const r = e.detect(...args);
    assert.equal(lsd.statusNames[-r], want, name);
  }
  assert.equal(e.config_profile(0, 0), -8);
  assert.equal(lsd.statusNames[-e.config_profile(0, end + 100)], 'out_of_bounds');
  assert.equal(lsd.statusNames[-e.config_validate(16)], 'out_of_bounds');
  assert.equal(lsd.statusNames[-e.workspace_size(8, 8, -4)], 'out_of_bounds');
  assert.equal(lsd.statusNames[-e.status_name(0, 16, 8)], 'out_of_bounds');
  assert.equal(lsd.statusNames[-e.status_name(99, cfg, 8)], 'invalid_argument');
  assert.equal(lsd.statusNames[-e.release(heapBase - 16)], 'out_of_bounds');
  assert.equal(lsd.statusNames[-e.release(mark + 1)], 'out_of_bounds');
  assert.equal(e.alloc(-1), 0, 'alloc fails instead of trapping');
  assert.equal(e.alloc(-64), 0, 'alloc fails instead of trapping');
  assert.equal(e.release(mark), 0);
  assert.equal(e.alloc(0), mark, 'release frees everything after the mark');
});
