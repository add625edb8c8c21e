// Browser test of report.html: runs a short LOLA walk through the `biped` binary, opens the report
// from file:// in headless Chromium (Debian's chromium, driven by playwright-core from the lock
// file) and checks: no console or page error, nothing fetched from elsewhere, the 3D canvas is not
// blank, every plot has data, scrubbing the time slider moves the robot, the title names the
// scenario, a legend explains the 3D overlay, desired traces are dashed and on top, joint plots are
// scaled to their motion.
// Usage: node report.test.mjs BIPED_BINARY WORK_DIR
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { test, after, before } from 'node:test';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { chromium } from 'playwright-core';

const CHROMIUM = '/usr/bin/chromium';
const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(here, '..', '..', '..');
const [biped, work] = process.argv.slice(2);
if (!biped || !work) {
  console.error('usage: node report.test.mjs BIPED_BINARY WORK_DIR');
  process.exit(2);
}

let browser, page;
const problems = [];  // console errors, page errors, requests that left the file

before(async () => {
  if (!fs.existsSync(CHROMIUM)) execFileSync(path.join(root, 'scripts', 'install-deps.sh'), { stdio: 'inherit' });
  fs.rmSync(work, { recursive: true, force: true });
  execFileSync(biped, ['run', path.join(root, 'config', 'scenarios', 'lola-walk.yaml'), '--out', work,
    '--set', 'duration=3'], { stdio: 'inherit' });

  browser = await chromium.launch({
    executablePath: CHROMIUM,
    headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
      '--disable-component-update', '--disable-sync',
      // WebGL without a GPU: ANGLE on SwiftShader, the software renderer that ships with Chromium.
      '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
  });
  page = await browser.newPage({ viewport: { width: 1400, height: 1000 } });
  page.on('console', (m) => { if (m.type() === 'error') problems.push(`console: ${m.text()}`); });
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  await page.route((url) => url.protocol !== 'file:', (route) => {
    problems.push(`request: ${route.request().url()}`);
    return route.abort();
  });
  await page.goto(pathToFileURL(path.join(work, 'report.html')).href);
  await page.waitForFunction(() => window.__report?.ready, null, { timeout: 20000 });
});

after(async () => {
  await browser?.close();
});

// Mean and standard deviation of the luminance of the 3D canvas, and a fingerprint of its pixels.
function canvasPixels() {
  return page.evaluate(() => {
    window.__report.render();
    const src = window.__report.canvas();
    const c = document.createElement('canvas');
    c.width = src.width;
    c.height = src.height;
    const ctx = c.getContext('2d');
    ctx.drawImage(src, 0, 0);
    const px = ctx.getImageData(0, 0, c.width, c.height).data;
    let sum = 0, sum2 = 0, hash = 0;
    for (let i = 0; i < px.length; i += 4) {
      const y = 0.299 * px[i] + 0.587 * px[i + 1] + 0.114 * px[i + 2];
      sum += y;
      sum2 += y * y;
      hash = (hash * 31 + px[i] + 7 * px[i + 1] + 13 * px[i + 2]) % 1000000007;
    }
    const n = px.length / 4, mean = sum / n;
    return { n, mean, std: Math.sqrt(Math.max(0, sum2 / n - mean * mean)), hash };
  });
}

test('the page loads with no console error, page error or outside request', () => {
  assert.deepEqual(problems, []);
});

test('the 3D canvas is not blank', async () => {
  const webgl = await page.evaluate(() => !!window.__report.canvas().getContext('webgl2'));
  assert.ok(webgl, 'WebGL 2 context');
  const p = await canvasPixels();
  assert.ok(p.n > 100000, `canvas has ${p.n} pixels`);
  assert.ok(p.std > 8, `luminance varies (std ${p.std.toFixed(1)}, mean ${p.mean.toFixed(1)})`);
});

test('every plot has data', async () => {
  const plots = await page.evaluate(() => window.__report.plots);
  assert.ok(plots.length >= 9 + 20, `${plots.length} plots`);
  for (const plot of plots) {
    assert.ok(plot.points >= 300, `${plot.title}: ${plot.points} points`);
    plot.series.forEach((n, i) => assert.ok(n > 0, `${plot.title}: series ${i + 1} has no value`));
  }
  const drawn = await page.locator('.uplot canvas').count();
  assert.equal(drawn, plots.length);
});

test('the title names the scenario; a legend explains the 3D overlay', async () => {
  assert.match(await page.title(), /^lola-walk \(lola\)/);
  assert.match(await page.locator('h1').textContent(), /lola-walk/);
  const items = await page.locator('#replay-legend .legend-item').allTextContents();
  for (const words of ['left foot', 'right foot', 'planned CoM trajectory', 'true CoM']) {
    assert.ok(items.some((t) => t.includes(words)), `legend: ${words} in ${JSON.stringify(items)}`);
  }
  const colours = await page.locator('#replay-legend .swatch').evaluateAll(
    (swatches) => swatches.map((s) => getComputedStyle(s).getPropertyValue('--color').trim()));
  assert.ok(new Set(colours).size >= 4, `distinct legend colours: ${colours}`);
  assert.match(await page.locator('#time-label').textContent(), /t = [0-9.]+ s, \w+/);
});

test('desired traces are dashed and drawn over the measured ones', async () => {
  const plots = await page.evaluate(() => window.__report.plots);
  const withDesired = plots.filter((p) => p.labels.some((l) => l.includes('desired')));
  assert.ok(withDesired.length >= 6, `${withDesired.length} plots with desired traces`);
  for (const p of withDesired) {
    const lastMeasured = p.labels.findLastIndex((l) => l.includes('measured'));
    p.labels.forEach((l, i) => {
      if (!l.includes('desired')) return;
      assert.ok(i > lastMeasured, `${p.title}: '${l}' is drawn after every measured trace`);
      assert.ok(p.dashed[i], `${p.title}: '${l}' is dashed`);
    });
  }
});

test('each joint plot is scaled to its own motion', async () => {
  const joints = await page.evaluate(() => window.__report.plots.filter((p) => p.labels[0] === 'angle'));
  const data = await page.evaluate(() => JSON.parse(document.getElementById('report-data').textContent).joints);
  assert.equal(joints.length, data.length);
  let narrower = 0;
  joints.forEach((p, k) => {
    const q = data[k].q.filter(Number.isFinite);
    const [lo, hi] = p.yRange;
    assert.ok(lo <= Math.min(...q) && Math.max(...q) <= hi, `${p.title}: the motion ${Math.min(...q)}..${Math.max(...q)} is inside the scale ${lo}..${hi}`);
    if (hi - lo < 0.5 * (data[k].upper - data[k].lower)) narrower += 1;
  });
  assert.ok(narrower > joints.length / 2, `${narrower} of ${joints.length} joints on a scale narrower than half their range`);
});

test('scrubbing the time slider moves the robot', async () => {
  const slider = page.locator('#time');
  await slider.fill('0.5');
  const before = await page.evaluate(() => window.__report.pelvis());
  const shotBefore = await page.locator('#viewer canvas').screenshot();
  const pixelsBefore = await canvasPixels();
  await slider.fill('2.9');
  assert.ok(Math.abs(await page.evaluate(() => window.__report.time()) - 2.9) < 1e-6);
  const later = await page.evaluate(() => window.__report.pelvis());
  const moved = Math.hypot(later[0] - before[0], later[1] - before[1], later[2] - before[2]);
  assert.ok(moved > 0.05, `pelvis moved ${moved.toFixed(3)} m between t = 0.5 s and 2.9 s`);
  const shotLater = await page.locator('#viewer canvas').screenshot();
  assert.ok(!shotBefore.equals(shotLater), 'the view changed');
  assert.notEqual((await canvasPixels()).hash, pixelsBefore.hash);
  assert.deepEqual(problems, []);
});

test('play advances the time, pause holds it; a click in a plot moves the replay there', async () => {
  await page.locator('#time').fill('1');
  await page.locator('#play').click();
  await page.waitForFunction(() => window.__report.time() > 1.2, null, { timeout: 10000 });
  // While playing, the software renderer redraws slowly: skip the wait for a still frame.
  await page.locator('#play').click({ force: true });
  const paused = await page.evaluate(() => window.__report.time());
  await page.waitForTimeout(300);
  assert.equal(await page.evaluate(() => window.__report.time()), paused);

  const plot = page.locator('.uplot .u-over').first();
  const box = await plot.boundingBox();
  await plot.click({ position: { x: 0.75 * box.width, y: 0.5 * box.height } });
  const t = await page.evaluate(() => window.__report.time());
  assert.ok(t > 1.8 && t < 2.7, `a click at 3/4 of the plot's width moved the replay to ${t.toFixed(2)} s`);
  assert.deepEqual(problems, []);
});
