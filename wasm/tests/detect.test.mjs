// Node test of the aaglsd wasm module (no npm packages): `node --test wasm/tests/`.
//
// Needs the module (cargo build -p aaglsd-wasm --release --target
// wasm32-unknown-unknown) and, for the comparison with the host, the files
// written by `cargo run -p aaglsd-wasm --release --example wasm_expected -- DIR`.
// wasm/tests/run.sh does all three. Paths: AAGLSD_WASM (the .wasm) and
// AAGLSD_WASM_EXPECTED (DIR), defaulting to $CARGO_TARGET_DIR or target/.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('../../', import.meta.url));
const targetDir = path.resolve(root, process.env.CARGO_TARGET_DIR ?? 'target');
const wasmPath =
  process.env.AAGLSD_WASM ??
  path.join(targetDir, 'wasm32-unknown-unknown', 'release', 'aaglsd_wasm.wasm');
const expectedDir = process.env.AAGLSD_WASM_EXPECTED ?? path.join(targetDir, 'wasm-test');

// Status codes returned (negated) by detect(); the numbers of AaglsdStatus.
const ZERO_DIMENSION = 1;
const IMAGE_TOO_LARGE = 2;
const INVALID_ARGUMENT = 11;

/** Instantiates the module (it imports nothing). */
async function load() {
  const { instance } = await WebAssembly.instantiate(readFileSync(wasmPath), {});
  return instance.exports;
}

/**
 * Runs detection on an 8-bit gray image (rows packed) and returns the status
 * or count, the summary and the segments as f32 values and bit patterns.
 */
function detect(wasm, pixels, width, height, profile) {
  new Uint8Array(wasm.memory.buffer, wasm.image_ptr(), width * height).set(pixels);
  const n = wasm.detect(width, height, profile);
  const summary = Array.from(new Uint32Array(wasm.memory.buffer, wasm.summary_ptr(), 7));
  const count = Math.max(n, 0);
  const floats = new Float32Array(wasm.memory.buffer, wasm.segments_ptr(), 4 * count);
  const bits = new Uint32Array(wasm.memory.buffer, wasm.segments_ptr(), 4 * count);
  const segments = [];
  const segmentBits = [];
  for (let i = 0; i < count; i++) {
    segments.push(Array.from(floats.subarray(4 * i, 4 * i + 4)));
    segmentBits.push(Array.from(bits.subarray(4 * i, 4 * i + 4)));
  }
  return { n, summary, segments, bits: segmentBits };
}

/** Reads a binary PGM as written by the wasm_expected example. */
function readPgm(file) {
  const bytes = readFileSync(file);
  const header = bytes.subarray(0, 64).toString('latin1');
  const m = /^P5\s+(\d+)\s+(\d+)\s+255\s/.exec(header);
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

test('exports', async () => {
  const wasm = await load();
  for (const f of ['detect', 'image_ptr', 'segments_ptr', 'summary_ptr', 'max_width',
                   'max_height', 'max_segments']) {
    assert.equal(typeof wasm[f], 'function', f);
  }
  assert.ok(wasm.memory instanceof WebAssembly.Memory);
  assert.deepEqual([wasm.max_width(), wasm.max_height(), wasm.max_segments()], [640, 480, 2048]);
});

test('the README rectangle has four sides', async () => {
  const wasm = await load();
  const { width, height, pixels } = rectangle();
  const r = detect(wasm, pixels, width, height, 0);
  assert.equal(r.n, 4);
  assert.equal(r.summary[0], 4);
  for (const [x0, y0, x1, y1] of r.segments) {
    assert.ok(Math.hypot(x1 - x0, y1 - y0) > 15, 'sides of 32 and 24 px');
  }
});

test('segments equal the host Rust output bit for bit', async () => {
  const wasm = await load();
  const expected = JSON.parse(readFileSync(path.join(expectedDir, 'expected.json'), 'utf8'));
  const img = readPgm(path.join(expectedDir, 'input.pgm'));
  assert.deepEqual([img.width, img.height], [expected.width, expected.height]);
  assert.equal(expected.runs.length, 3);
  for (const run of expected.runs) {
    const r = detect(wasm, img.pixels, img.width, img.height, run.profile);
    assert.equal(r.n, run.count, `profile ${run.profile}: count`);
    assert.deepEqual(r.summary, run.summary, `profile ${run.profile}: summary`);
    assert.deepEqual(r.bits, run.bits, `profile ${run.profile}: segments`);
  }
});

test('errors are negative status codes and zero the summary', async () => {
  const wasm = await load();
  const { width, height, pixels } = rectangle();
  const cases = [
    [0, height, 0, ZERO_DIMENSION],
    [width, 0, 0, ZERO_DIMENSION],
    [641, 1, 0, IMAGE_TOO_LARGE],
    [1, 481, 0, IMAGE_TOO_LARGE],
    [0xffffffff, 0xffffffff, 0, IMAGE_TOO_LARGE],
    [width, height, 3, INVALID_ARGUMENT],
  ];
  for (const [w, h, profile, status] of cases) {
    assert.equal(detect(wasm, pixels, width, height, 0).n, 4); // a summary to clear
    assert.equal(wasm.detect(w, h, profile), -status, `${w}x${h} profile ${profile}`);
    const summary = new Uint32Array(wasm.memory.buffer, wasm.summary_ptr(), 7);
    assert.ok(summary.every((v) => v === 0), 'summary zeroed');
  }
});
