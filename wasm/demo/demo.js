// The aaglsd browser demo: decode a picture with the browser, convert it to
// gray (OpenCV's BT.601 integer luma, as the Python package does), run the
// wasm detector, draw the segments over the picture. Plain ES module, no
// bundler. `?image=URL` picks the first picture (default: castle1.png,
// copied here by build.sh). Each segment is drawn with an opacity that
// grows with its score (the Rust CLI's SVG overlay does the same). The page publishes each result on
// `window.aaglsdResult` and sets `data-state="done"` on <body> (with a run
// counter in `data-runs`) for the browser test.
import { Aaglsd, PROFILES, rgbaToGray } from './aaglsd.js';

/** [field, min, max, step]: the sliders, in Config units. */
const SLIDERS = [
  ['magnitude_threshold', 0, 60, 0.01],
  ['min_length_px', 0, 100, 0.5],
  ['align_tolerance_deg', 1, 60, 0.5],
  ['anchor_density', 0, 1, 0.01],
  ['aligned_density', 0, 1, 0.01],
  ['min_groups', 1, 12, 1],
];

const $ = (id) => document.getElementById(id);
const canvas = $('canvas');
const stats = $('stats');
const state = { lsd: null, image: null, gray: null, width: 0, height: 0, name: '',
  profile: 'default', config: null, result: null, runs: 0, pending: false, urls: [] };

/**
 * The stroke opacity of each score, linear in it: 1 for the image's highest,
 * 0.25 for a score of 0, as the Rust CLI's SVG overlay
 * (aaglsd_support::svg::score_opacity).
 */
export function scoreOpacity(scores) {
  const best = Math.max(0, ...scores);
  return Array.from(scores, (s) => (best > 0 ? 0.25 + 0.75 * Math.max(s, 0) / best : 1));
}

/** Shortest decimal that reads back as the same f32: Rust's `{}` of an f32. */
export function f32Text(v) {
  for (let p = 1; p <= 9; p++) {
    const s = v.toPrecision(p);
    if (Math.fround(Number(s)) === v) return String(Number(s));
  }
  return String(v);
}

function setStats(text, isError = false) {
  stats.textContent = text;
  stats.classList.toggle('error', isError);
}

function buildSliders() {
  const box = $('sliders');
  for (const [name, min, max, step] of SLIDERS) {
    const label = document.createElement('label');
    label.innerHTML = `<span>${name} <span class="value" id="v-${name}"></span></span>`;
    const input = Object.assign(document.createElement('input'),
      { type: 'range', id: `s-${name}`, min, max, step });
    input.addEventListener('input', () => {
      state.config[name] = Number(input.value);
      $(`v-${name}`).textContent = input.value;
      schedule();
    });
    label.append(input);
    box.append(label);
  }
  $('merge').addEventListener('change', (ev) => {
    state.config.merge = ev.target.checked ? 1 : 0;
    schedule();
  });
  $('profile').addEventListener('change', (ev) => setProfile(ev.target.value));
  $('show-image').addEventListener('change', () => draw());
}

/** Loads a profile's configuration and shows it on the controls. */
function setProfile(name) {
  state.profile = name;
  state.config = state.lsd.profile(name);
  for (const [field] of SLIDERS) {
    const input = $(`s-${field}`);
    input.value = String(state.config[field]);
    $(`v-${field}`).textContent = input.value;
  }
  $('merge').checked = state.config.merge !== 0;
  schedule();
}

/** Decodes a picture (PNG, JPEG) into RGBA and gray pixels. */
async function loadImage(blob, name) {
  const bitmap = await createImageBitmap(blob, {
    colorSpaceConversion: 'none', premultiplyAlpha: 'none',
  });
  const { width, height } = bitmap;
  const scratch = document.createElement('canvas');
  Object.assign(scratch, { width, height });
  const ctx = scratch.getContext('2d', { willReadFrequently: true });
  ctx.drawImage(bitmap, 0, 0);
  const rgba = ctx.getImageData(0, 0, width, height).data;
  Object.assign(state, { image: bitmap, width, height, name,
    gray: rgbaToGray(rgba, width, height) });
  canvas.width = width;
  canvas.height = height;
  schedule();
}

async function loadUrl(url) {
  const res = await fetch(url);
  if (!res.ok) throw new Error(`${url}: HTTP ${res.status}`);
  await loadImage(await res.blob(), url.split('/').pop());
}

/** Re-runs the detector once per frame at most, however many inputs changed. */
function schedule() {
  if (state.pending) return;
  state.pending = true;
  requestAnimationFrame(() => {
    state.pending = false;
    detect();
  });
}

function detect() {
  if (!state.gray || !state.config) return;
  document.body.dataset.state = 'running';
  try {
    state.result = state.lsd.detect(state.gray, state.width, state.height, state.config);
  } catch (err) {
    state.result = null;
    setStats(String(err.message ?? err), true);
    draw();
    document.body.dataset.state = 'error';
    return;
  }
  const r = state.result;
  const drawn = draw();
  const dropped = r.summary.dropped_segments ? `, ${r.summary.dropped_segments} dropped` : '';
  setStats(`${r.count} segments${dropped} in ${r.ms.toFixed(1)} ms · ${state.width}×${state.height}` +
    ` · ${state.name} · ${state.lsd.simd ? 'wasm simd128' : 'wasm (no simd128)'}`);
  updateDownloads();
  window.aaglsdResult = {
    width: state.width, height: state.height, name: state.name, profile: state.profile,
    config: { ...state.config }, count: r.count, summary: r.summary, ms: r.ms, simd: state.lsd.simd,
    // The coordinates handed to the canvas, as f32 bit patterns.
    drawnBits: Array.from(new Uint32Array(drawn.buffer)),
    scoreBits: Array.from(new Uint32Array(r.scores.buffer, r.scores.byteOffset, r.count)),
  };
  state.runs += 1;
  document.body.dataset.runs = String(state.runs);
  document.body.dataset.state = 'done';
}

/** Draws the picture and the segments; returns the coordinates drawn. */
function draw() {
  const ctx = canvas.getContext('2d');
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  ctx.fillStyle = '#fff';
  ctx.fillRect(0, 0, canvas.width, canvas.height);
  if (state.image && $('show-image').checked) {
    ctx.globalAlpha = 0.75;
    ctx.drawImage(state.image, 0, 0);
    ctx.globalAlpha = 1;
  }
  const segs = state.result ? state.result.segments : new Float32Array(0);
  const alpha = scoreOpacity(state.result ? state.result.scores : []);
  const drawn = new Float32Array(segs.length);
  // Segment coordinates are pixel centres: pixel (col, row) is centred at
  // (col, row), i.e. at canvas (col + 0.5, row + 0.5).
  ctx.translate(0.5, 0.5);
  ctx.lineWidth = Math.max(1.5, canvas.width / 500);
  ctx.lineCap = 'round';
  ctx.strokeStyle = '#e53935';
  for (let i = 0; i < segs.length; i += 4) {
    drawn.set(segs.subarray(i, i + 4), i);
    ctx.globalAlpha = alpha[i / 4];
    ctx.beginPath();
    ctx.moveTo(drawn[i], drawn[i + 1]);
    ctx.lineTo(drawn[i + 2], drawn[i + 3]);
    ctx.stroke();
  }
  ctx.globalAlpha = 1;
  return drawn;
}

/** `x0 y0 x1 y1` lines, as the Rust CLI prints them; with `scores`, a fifth
 * column, as `detect --scores` prints it. */
function segmentsText(segs, scores = null) {
  let s = '';
  for (let i = 0; i < segs.length; i += 4) {
    s += `${f32Text(segs[i])} ${f32Text(segs[i + 1])} ${f32Text(segs[i + 2])} ${f32Text(segs[i + 3])}`;
    s += scores ? ` ${f32Text(scores[i / 4])}\n` : '\n';
  }
  return s;
}

function segmentsSvg(segs, scores, width, height) {
  const alpha = scoreOpacity(scores);
  const lines = [];
  for (let i = 0; i < segs.length; i += 4) {
    lines.push(`  <line x1="${f32Text(segs[i])}" y1="${f32Text(segs[i + 1])}" ` +
      `x2="${f32Text(segs[i + 2])}" y2="${f32Text(segs[i + 3])}" ` +
      `stroke-opacity="${alpha[i / 4].toFixed(2)}"/>`);
  }
  return `<svg xmlns="http://www.w3.org/2000/svg" width="${width}" height="${height}" ` +
    `viewBox="-0.5 -0.5 ${width} ${height}">\n` +
    `<g stroke="#e53935" stroke-width="1" stroke-linecap="round">\n${lines.join('\n')}\n</g>\n</svg>\n`;
}

function updateDownloads() {
  for (const url of state.urls) URL.revokeObjectURL(url);
  const { segments: segs, scores } = state.result;
  const stem = state.name.replace(/\.[^.]*$/, '') || 'segments';
  const link = (id, text, type, ext) => {
    const url = URL.createObjectURL(new Blob([text], { type }));
    Object.assign($(id), { href: url, download: `${stem}.${ext}` });
    return url;
  };
  state.urls = [
    link('download-txt', segmentsText(segs), 'text/plain', 'txt'),
    link('download-scored', segmentsText(segs, scores), 'text/plain', 'scored.txt'),
    link('download-svg', segmentsSvg(segs, scores, state.width, state.height), 'image/svg+xml',
      'svg'),
  ];
}

function wireFiles() {
  const open = (file) => {
    if (file) loadImage(file, file.name).catch((err) => setStats(`${file.name}: ${err.message}`, true));
  };
  $('file').addEventListener('change', (ev) => open(ev.target.files[0]));
  window.addEventListener('dragover', (ev) => {
    ev.preventDefault();
    document.body.classList.add('dragging');
  });
  window.addEventListener('dragleave', () => document.body.classList.remove('dragging'));
  window.addEventListener('drop', (ev) => {
    ev.preventDefault();
    document.body.classList.remove('dragging');
    open(ev.dataTransfer.files[0]);
  });
}

async function main() {
  const params = new URLSearchParams(location.search);
  // The simd128 module where the browser has simd128, else the plain one
  // (?simd=0 forces the plain one).
  const modules = { plain: 'aaglsd_wasm.wasm', simd: 'aaglsd_wasm_simd.wasm' };
  state.lsd = await Aaglsd.load(modules, params.get('simd') === '0' ? { simd: false } : {});
  buildSliders();
  wireFiles();
  const profile = params.get('profile') ?? 'default';
  $('profile').value = PROFILES.includes(profile) ? profile : 'default';
  setProfile($('profile').value);
  await loadUrl(params.get('image') ?? 'castle1.png');
}

main().catch((err) => {
  setStats(`cannot start: ${err.message ?? err}`, true);
  document.body.dataset.state = 'error';
});
