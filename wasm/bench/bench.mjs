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
// With AAGLSD_BENCH_CHROMIUM (a Chromium binary, e.g. /usr/bin/chromium, and
// puppeteer-core installed in wasm/demo/test: wasm/demo/test/run.sh does
// that), the same modules are timed in headless Chromium too (columns
// chromium_plain, chromium_simd), in the same interleaving, through the same
// wrapper; their output is checked like node's.
//
// Environment: AAGLSD_WASM (the plain .wasm), AAGLSD_WASM_SIMD (the simd128
// .wasm; skipped when unset or missing), AAGLSD_BENCH_NATIVE (the example's
// binary), AAGLSD_BENCH_WORK (where the PGMs go), AAGLSD_BENCH_REPS (default
// 7), AAGLSD_BENCH_DATA (the image folder), AAGLSD_BENCH_CHROMIUM.
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, readdirSync, rmSync } from 'node:fs';
import { createRequire } from 'node:module';
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

// Headless Chromium: one blank page holding the wrapper and the modules.
let browser;
let page;
let profileDir;
if (env.AAGLSD_BENCH_CHROMIUM) {
  const require = createRequire(path.join(root, 'wasm', 'demo', 'test', 'package.json'));
  const puppeteer = (await import(require.resolve('puppeteer-core'))).default;
  profileDir = mkdtempSync(path.join(os.tmpdir(), 'aaglsd-bench-chromium-'));
  browser = await puppeteer.launch({
    executablePath: env.AAGLSD_BENCH_CHROMIUM,
    headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--no-first-run', '--disable-background-networking',
      '--disable-component-update', '--disable-sync', `--user-data-dir=${profileDir}`],
  });
  page = await browser.newPage();
  const simd = await page.evaluate(async (wrapper, mods) => {
    const url = URL.createObjectURL(new Blob([wrapper], { type: 'text/javascript' }));
    const { Aaglsd } = await import(url);
    window.lsds = {};
    for (const [name, b64] of mods) {
      window.lsds[name] = await Aaglsd.instantiate(Uint8Array.from(atob(b64), (c) => c.charCodeAt(0)));
    }
    window.timeModule = (name, b64, width, height, reps) => {
      const pixels = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
      const lsd = window.lsds[name];
      const cfg = lsd.profile('default');
      const ms = [];
      let first;
      for (let i = 0; i <= reps; i++) {
        const r = lsd.detect(pixels, width, height, cfg);
        if (i === 0) {
          first = { count: r.count, segments: Array.from(new Uint32Array(r.segments.buffer)),
            scores: Array.from(new Uint32Array(r.scores.buffer)) };
        } else {
          ms.push(r.ms);
        }
      }
      return { ms, first };
    };
    return Object.fromEntries(Object.entries(window.lsds).map(([k, v]) => [k, v.simd]));
  }, readFileSync(path.join(root, 'wasm', 'js', 'aaglsd.mjs'), 'utf8'),
  modules.map(([name, file]) => [name, readFileSync(file).toString('base64')]));
  console.log(`chromium: ${await browser.version()}, simd128 per module: ${JSON.stringify(simd)}, ` +
    `simdSupported: ${await page.evaluate(() => WebAssembly.validate(new Uint8Array([0, 97, 115,
      109, 1, 0, 0, 0, 1, 5, 1, 96, 0, 1, 123, 3, 2, 1, 0, 10, 10, 1, 8, 0, 65, 0, 253, 15, 253,
      98, 11])))}`);
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

async function timeChromium(name, img, want) {
  const { ms, first } = await page.evaluate((...a) => window.timeModule(...a), name,
    Buffer.from(img.pixels).toString('base64'), img.width, img.height, reps);
  const r = { count: first.count, segments: new Float32Array(new Uint32Array(first.segments).buffer),
    scores: new Float32Array(new Uint32Array(first.scores).buffer) };
  if (r.count !== want.count || hash(r) !== want.hash) {
    throw new Error(`${want.image}: the ${name} module in Chromium gives ${r.count} segments ` +
      `(hash ${hash(r)}), native ${want.count} (hash ${want.hash})`);
  }
  return median(ms);
}

const wasmCols = [...modules.map(([n]) => n), ...(page ? modules.map(([n]) => `chromium_${n}`) : [])];
const cols = ['native', 'native_fast', ...wasmCols];
const fmt = (x, w = 9) => (Number.isFinite(x) ? x.toFixed(2) : '-').padStart(w);
console.log(`wasm bench: ${images.length} images, ${reps} runs each (median), node ` +
  `${process.version}, ${os.cpus()[0]?.model ?? '?'}, load ${os.loadavg().map((l) => l.toFixed(2)).join(' ')}`);
const width = (c) => Math.max(12, c.length + 2);
const ratioCols = wasmCols.map((n) => `${n}/native`);
console.log(`${'image'.padEnd(16)}${cols.map((c) => c.padStart(width(c))).join('')}   ` +
  ratioCols.map((c) => c.padStart(width(c))).join(''));
const rows = [];
for (const [k, image] of images.entries()) {
  const p = spawnSync(native, ['--reps', String(reps), work, image], { encoding: 'utf8' });
  if (p.status !== 0) throw new Error(`${native} ${image}: ${p.stderr || p.error}`);
  const want = JSON.parse(p.stdout.trim());
  const img = readPgm(want.pgm);
  const row = { image: path.basename(image), native: want.ms, native_fast: want.ms_fast };
  // Alternate which module goes first, image by image.
  const order = k % 2 ? [...modules].reverse() : modules;
  for (const [name] of order) row[name] = timeModule(name, img, want);
  if (page) for (const [name] of order) row[`chromium_${name}`] = await timeChromium(name, img, want);
  rows.push(row);
  console.log(`${row.image.padEnd(16)}${cols.map((c) => fmt(row[c], width(c))).join('')}   ` +
    wasmCols.map((n, i) => fmt(row[n] / row.native, width(ratioCols[i]))).join(''));
}
if (browser) {
  await browser.close();
  rmSync(profileDir, { recursive: true, force: true });
}

console.log(`\nmedian over ${rows.length} images (ms per image):`);
for (const c of cols) console.log(`  ${c.padEnd(16)}${fmt(median(rows.map((r) => r[c])))}`);
console.log('median over images of the per-image ratio:');
const ratios = [...wasmCols.map((n) => [n, 'native']), ...wasmCols.map((n) => [n, 'native_fast'])];
if (lsds.simd && lsds.plain) ratios.push(['simd', 'plain']);
if (page && lsds.simd && lsds.plain) ratios.push(['chromium_simd', 'chromium_plain']);
for (const [a, b] of ratios) {
  console.log(`  ${`${a}/${b}`.padEnd(30)}${fmt(median(rows.map((r) => r[a] / r[b])), 6)}`);
}
console.log(`load after: ${os.loadavg().map((l) => l.toFixed(2)).join(' ')}`);
