// Timing bench of the wasm modules against the native core (no npm packages):
//   node wasm/bench/bench.mjs [IMAGE...]
// wasm/bench/run.sh builds what it needs and runs it; see wasm/README.md.
//
// Per image (default: every .jpg of ../shared/data/yorkurban beside the
// repository, 640x480), interleaved so that load from elsewhere touches every
// column alike: the native example (wasm/examples/wasm_bench_native.rs, run
// once per image) decodes the image, writes it as a PGM and times
// aaglsd::detect natively; then each module (the plain one, and the simd128
// one when present, in alternating order) gets one warm-up run and REPS
// timed runs of the wasm call alone (Aaglsd.detect's `ms`). Everything runs
// Config::DEFAULT with the workspace the module uses (Workspace::bytes_needed).
// Each time is the median of its REPS runs; the summary gives the median over
// images of the times and of the per-image ratios. Every module's output is
// checked against the native one (segment count and a hash of the bits).
//
// Environment: AAGLSD_WASM (the plain .wasm), AAGLSD_WASM_SIMD (the simd128
// .wasm; skipped when unset or missing), AAGLSD_BENCH_NATIVE (the example's
// binary), AAGLSD_BENCH_WORK (where the PGMs go), AAGLSD_BENCH_REPS (default
// 7), AAGLSD_BENCH_DATA (the image folder).
import { spawnSync } from 'node:child_process';
import { existsSync, readFileSync, readdirSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import { Aaglsd } from '../js/aaglsd.mjs';

const root = fileURLToPath(new URL('../../', import.meta.url));
const targetDir = path.resolve(root, process.env.CARGO_TARGET_DIR ?? 'target');
const env = process.env;
const reps = Number(env.AAGLSD_BENCH_REPS ?? 7);
const work = env.AAGLSD_BENCH_WORK ?? path.join(targetDir, 'wasm-bench');
const native = env.AAGLSD_BENCH_NATIVE ??
  path.join(targetDir, 'release', 'examples', 'wasm_bench_native');
const dataDir = env.AAGLSD_BENCH_DATA ?? path.resolve(root, '..', 'shared', 'data', 'yorkurban');

let images = process.argv.slice(2);
if (images.length === 0) {
  images = readdirSync(dataDir).filter((f) => /\.jpe?g$/i.test(f)).sort()
    .map((f) => path.join(dataDir, f));
}
if (images.length === 0) throw new Error(`no images (${dataDir})`);

const modules = [['plain', env.AAGLSD_WASM], ['simd', env.AAGLSD_WASM_SIMD]]
  .filter(([, file]) => file && existsSync(file));
if (modules.length === 0) throw new Error('AAGLSD_WASM: no module to time');
const lsds = {};
for (const [name, file] of modules) {
  lsds[name] = await Aaglsd.instantiate(readFileSync(file));
  if (lsds[name].simd !== undefined && lsds[name].simd !== (name === 'simd')) {
    throw new Error(`${file}: simd128 is ${lsds[name].simd}, expected for the ${name} module`);
  }
}

function median(v) {
  const s = [...v].sort((a, b) => a - b);
  const n = s.length;
  return n % 2 ? s[(n - 1) / 2] : (s[n / 2 - 1] + s[n / 2]) / 2;
}

/** wasm_bench_native's FNV-1a over the f32 bit patterns, x0 y0 x1 y1 score. */
function hash(r) {
  const seg = new Uint32Array(r.segments.buffer, r.segments.byteOffset, r.segments.length);
  const score = new Uint32Array(r.scores.buffer, r.scores.byteOffset, r.scores.length);
  let h = 0x811c9dc5;
  for (let i = 0; i < r.count; i++) {
    for (const w of [...seg.subarray(4 * i, 4 * i + 4), score[i]]) {
      for (let k = 0; k < 4; k++) h = Math.imul(h ^ ((w >>> (8 * k)) & 0xff), 0x01000193) >>> 0;
    }
  }
  return h;
}

function readPgm(file) {
  const bytes = readFileSync(file);
  const m = /^P5\s+(\d+)\s+(\d+)\s+255\s/.exec(bytes.subarray(0, 64).toString('latin1'));
  if (!m) throw new Error(`${file}: not an 8-bit P5 PGM`);
  const [width, height] = [Number(m[1]), Number(m[2])];
  return { width, height, pixels: bytes.subarray(m[0].length, m[0].length + width * height) };
}

function timeModule(name, img, want) {
  const lsd = lsds[name];
  const cfg = lsd.profile('default');
  const ms = [];
  for (let i = 0; i <= reps; i++) {
    const r = lsd.detect(img.pixels, img.width, img.height, cfg);
    if (i === 0 && (r.count !== want.count || hash(r) !== want.hash)) {
      throw new Error(`${want.image}: the ${name} module gives ${r.count} segments ` +
        `(hash ${hash(r)}), native ${want.count} (hash ${want.hash})`);
    }
    if (i > 0) ms.push(r.ms);
  }
  return median(ms);
}

const cols = ['native', 'native_fast', ...modules.map(([n]) => n)];
const fmt = (x, w = 9) => (Number.isFinite(x) ? x.toFixed(2) : '-').padStart(w);
console.log(`wasm bench: ${images.length} images, ${reps} runs each (median), node ` +
  `${process.version}, ${os.cpus()[0]?.model ?? '?'}, load ${os.loadavg().map((l) => l.toFixed(2)).join(' ')}`);
console.log(`${'image'.padEnd(16)}${cols.map((c) => c.padStart(12)).join('')}   ` +
  modules.map(([n]) => `${n}/native`.padStart(12)).join(''));
const rows = [];
images.forEach((image, k) => {
  const p = spawnSync(native, ['--reps', String(reps), work, image], { encoding: 'utf8' });
  if (p.status !== 0) throw new Error(`${native} ${image}: ${p.stderr || p.error}`);
  const want = JSON.parse(p.stdout.trim());
  const img = readPgm(want.pgm);
  const row = { image: path.basename(image), native: want.ms, native_fast: want.ms_fast };
  // Alternate which module goes first, image by image.
  const order = k % 2 ? [...modules].reverse() : modules;
  for (const [name] of order) row[name] = timeModule(name, img, want);
  rows.push(row);
  console.log(`${row.image.padEnd(16)}${cols.map((c) => fmt(row[c], 12)).join('')}   ` +
    modules.map(([n]) => fmt(row[n] / row.native, 12)).join(''));
});

console.log(`\nmedian over ${rows.length} images (ms per image):`);
for (const c of cols) console.log(`  ${c.padEnd(12)}${fmt(median(rows.map((r) => r[c])))}`);
console.log('median over images of the per-image ratio:');
const ratios = [...modules.map(([n]) => [n, 'native']), ...modules.map(([n]) => [n, 'native_fast'])];
if (lsds.simd && lsds.plain) ratios.push(['simd', 'plain']);
for (const [a, b] of ratios) {
  console.log(`  ${`${a}/${b}`.padEnd(20)}${fmt(median(rows.map((r) => r[a] / r[b])), 6)}`);
}
console.log(`load after: ${os.loadavg().map((l) => l.toFixed(2)).join(' ')}`);
