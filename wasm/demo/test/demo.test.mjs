// Browser test of the demo page (wasm/demo/test/run.sh sets it up): headless
// Debian Chromium driven by puppeteer-core. Loads the page with the bundled
// image, waits for each result, and checks that the segments the page drew
// equal the host Rust core's bit for bit (default and paper profiles, and a
// configuration set with the sliders) and so are their scores, that the text
// downloads equal the Rust CLI's output byte for byte (plain and --scores),
// that the SVG holds every segment, shaded by score, and that nothing was
// logged as an error. Saves a screenshot.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';

import puppeteer from 'puppeteer-core';

const url = process.env.AAGLSD_DEMO_URL;
const work = process.env.AAGLSD_DEMO_WORK;
const chromium = process.env.CHROMIUM ?? '/usr/bin/chromium';

/** Waits for the page's `n`-th finished run whose config passes `want`. */
async function result(page, n, want = {}) {
  await page.waitForFunction(
    (n, want) => document.body.dataset.state === 'done' &&
      Number(document.body.dataset.runs) >= n &&
      Object.entries(want).every(([k, v]) => window.aaglsdResult.config[k] === v),
    { timeout: 30_000 }, n, want);
  return page.evaluate(() => ({ ...window.aaglsdResult, runs: Number(document.body.dataset.runs) }));
}

function assertSameSegments(r, run, label) {
  assert.equal(r.count, run.count, `${label}: count`);
  assert.deepEqual(Object.values(r.summary), run.summary, `${label}: summary`);
  // run.bits: [x0, y0, x1, y1, score] per segment.
  const want = run.bits.flatMap((b) => b.slice(0, 4));
  assert.equal(r.drawnBits.length, want.length, `${label}: drawn coordinates`);
  assert.deepEqual(r.drawnBits, want, `${label}: drawn segments, bit for bit`);
  assert.deepEqual(r.scoreBits, run.bits.map((b) => b[4]), `${label}: scores, bit for bit`);
}

test('the demo draws the host segments in headless Chromium', async () => {
  assert.ok(url && work, 'run through wasm/demo/test/run.sh');
  const expected = JSON.parse(readFileSync(path.join(work, 'expected.json'), 'utf8'));
  const cliText = readFileSync(path.join(work, 'cli-default.txt'), 'utf8');
  const cliScored = readFileSync(path.join(work, 'cli-scores.txt'), 'utf8');
  const profileDir = mkdtempSync(path.join(os.tmpdir(), 'aaglsd-chromium-'));
  const browser = await puppeteer.launch({
    executablePath: chromium,
    headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync',
      `--user-data-dir=${profileDir}`],
  });
  const problems = [];
  try {
    const page = await browser.newPage();
    page.on('console', (m) => {
      if (m.type() === 'error') problems.push(`console.error: ${m.text()}`);
    });
    page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
    page.on('requestfailed', (r) => problems.push(`request failed: ${r.url()}`));
    page.on('response', (r) => {
      if (r.status() >= 400) problems.push(`HTTP ${r.status()}: ${r.url()}`);
    });
    await page.setViewport({ width: 1040, height: 620 });
    await page.goto(`${url}?image=castle1.png`, { waitUntil: 'load' });

    // Default profile, as loaded.
    let r = await result(page, 1);
    assert.deepEqual([r.width, r.height, r.name], [expected.width, expected.height, 'castle1.png']);
    assertSameSegments(r, expected.runs[0], 'default');
    const stats = await page.$eval('#stats', (el) => el.textContent);
    assert.match(stats, new RegExp(`^${r.count} segments in \\d+\\.\\d ms · 633×470`));
    // Chromium has simd128: the page loaded that module, and says so.
    assert.equal(r.simd, true, 'the simd128 module runs');
    assert.match(stats, / · wasm simd128$/);
    await page.screenshot({ path: path.join(work, 'screenshot.png') });

    // The downloads, read through their links.
    const [txt, scored, svg] = await page.evaluate(() => Promise.all(
      ['download-txt', 'download-scored', 'download-svg'].map((id) =>
        fetch(document.getElementById(id).href).then((res) => res.text()))));
    assert.equal(txt, cliText, 'text download = Rust CLI output');
    assert.equal(scored, cliScored, 'text with scores = Rust CLI output with --scores');
    assert.equal((svg.match(/<line /g) ?? []).length, r.count);
    const opacities = [...svg.matchAll(/stroke-opacity="([0-9.]+)"/g)].map((m) => Number(m[1]));
    assert.equal(opacities.length, r.count);
    const best = Math.max(...r.scoreBits.map((b) => new Float32Array(new Uint32Array([b]).buffer)[0]));
    assert.equal(Math.max(...opacities), 1, 'the highest score opaque');
    assert.ok(Math.min(...opacities) >= 0.25 && Math.min(...opacities) < 0.5,
      `the weakest faint (best score ${best})`);
    assert.ok(svg.startsWith('<svg xmlns="http://www.w3.org/2000/svg" width="633" height="470"'));

    // The paper profile, from the selector.
    await page.select('#profile', 'paper');
    r = await result(page, r.runs + 1, { merge: 1 });
    assertSameSegments(r, expected.runs[2], 'paper');

    // A custom configuration, with the sliders and the merge toggle.
    const custom = expected.runs[3];
    for (const [name, v] of Object.entries(custom.set)) {
      if (name === 'merge') continue;
      await page.evaluate((name, v) => {
        const el = document.getElementById(`s-${name}`);
        el.value = String(v);
        el.dispatchEvent(new Event('input'));
      }, name, v);
    }
    await page.click('#merge');
    r = await result(page, r.runs + 1, custom.set);
    assertSameSegments(r, custom, 'sliders');

    // The plain module (?simd=0): the same segments, and the page says so.
    await page.goto(`${url}?image=castle1.png&simd=0`, { waitUntil: 'load' });
    r = await result(page, 1);
    assert.equal(r.simd, false, 'the plain module runs');
    assertSameSegments(r, expected.runs[0], 'default, plain module');
    assert.match(await page.$eval('#stats', (el) => el.textContent), / · wasm \(no simd128\)$/);
  } finally {
    await browser.close();
    rmSync(profileDir, { recursive: true, force: true });
  }
  assert.deepEqual(problems, [], 'no console error, page error or failed request');
});
