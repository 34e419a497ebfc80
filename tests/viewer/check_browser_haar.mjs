// The real-browser test of `prt view` on a Haar-wavelet file (run_browser_check.sh bakes the demo
// with --basis haar and renders it with prt relight): headless Chromium, puppeteer-core, the page
// at 640×360 against `prt relight`'s PNG of the same setting:
//   1. defaults (the manifest's camera and exposure, 200 terms) against prt relight with none;
//   2. rotate=0,0,0 and rotate=90,0,0 at the manifest's exposure against --rotate …;
//   3. terms=8&rotate=90,0,0 against --terms 8 --rotate 90,0,0 (8 terms change the CPU's picture
//      by ≥ 10%, so the page must apply the count it is given);
//   4. the change from 0° to 90°: it must change the CPU's picture by ≥ 10%, and the page's change
//      may differ from the CPU's by ≤ 10% of it.
// The object's pixels, the metric and the mask are those of check_browser.mjs (the page drawn
// without background, less a 1-pixel rim; 8-bit display values; relative RMS =
// √(Σ(gpu − cpu)²/Σ cpu²)). Tolerance 3% a picture: the page computes the same per-vertex
// radiance as prt relight (same cubes, transform, term selection and sparse sum, to float
// rounding: check_haar_js.mjs), so what remains is rasterisation — Gouraud interpolation on the
// GPU against the CPU's barycentric one, and MSAA against 3×3 samples a pixel where a pixel
// straddles triangles whose radiance jumps, which the sharp shadows of an all-frequency light
// have many more of than SH's. Measured 1–2% (docs/VIEWER.md); a rotation applied the wrong way,
// a wrong face or a missing albedo gives 10% or more.
// Usage: node check_browser_haar.mjs URL OUT_DIR   (OUT_DIR holds manifest.json, cpu_default.png,
// cpu_r0.png, cpu_r90.png, cpu_r90_k8.png; receives the screenshots and haar_timing.json).
import { readFileSync, writeFileSync } from 'node:fs';
import { launchBrowser, makeChecks, makeShooter, maskCount, median as middle, objectMask, readRgb, relativeRms } from './browser.mjs';

const [url, out] = process.argv.slice(2);
const WIDTH = 640, HEIGHT = 360;
const TOLERANCE = 0.03, MIN_CHANGE = 0.10, CHANGE_TOLERANCE = 0.10;
const { check, failures } = makeChecks();
const browser = await launchBrowser(out);
const shoot = makeShooter(browser, url, out, WIDTH, HEIGHT);
const cpu = (name) => readRgb(out, name);

// Times of light changes in the page: n rotations by 7° of yaw, each a full change.
function timeLightChanges() {
  const { context, state, render } = window.prtViewer;
  const changes = [];
  for (let i = 0; i < 10; ++i) {
    state.rotation[0] += 7;
    render();
    changes.push(context.haar.lastChange);
  }
  return changes;
}

try {
  const manifest = JSON.parse(readFileSync(`${out}/manifest.json`, 'utf8'));
  check(manifest.kind === 'haar' && manifest.haar.default_terms === 200, `the manifest describes a Haar file (cube ${manifest.haar.cube_size}, ${manifest.haar.entries} entries)`);
  const fixed = `ui=0&exposure=${manifest.exposure_ev}`;
  const mask = objectMask((await shoot(`${fixed}&background=0`, 'gpu_mask')).image);
  const count = maskCount(mask);
  check(count > 0.2 * WIDTH * HEIGHT, `the object covers ${count} pixels of ${WIDTH * HEIGHT}`);
  const e0 = relativeRms((await shoot('ui=0', 'gpu_default')).image.rgb, cpu('cpu_default'), mask);
  check(e0 <= TOLERANCE, `defaults (camera, exposure, 200 terms): relative RMS ${(100 * e0).toFixed(2)}% against prt relight (≤ ${100 * TOLERANCE}%)`);
  const g0 = (await shoot(`${fixed}&rotate=0,0,0`, 'gpu_r0')).image.rgb;
  const g90 = (await shoot(`${fixed}&rotate=90,0,0`, 'gpu_r90')).image.rgb;
  const c0 = cpu('cpu_r0'), c90 = cpu('cpu_r90');
  const e1 = relativeRms(g0, c0, mask), e2 = relativeRms(g90, c90, mask);
  check(e1 <= TOLERANCE, `rotate 0,0,0: relative RMS ${(100 * e1).toFixed(2)}%`);
  check(e2 <= TOLERANCE, `rotate 90,0,0: relative RMS ${(100 * e2).toFixed(2)}%`);
  const gk = (await shoot(`${fixed}&rotate=90,0,0&terms=8`, 'gpu_r90_k8')).image.rgb, ck = cpu('cpu_r90_k8');
  const ek = relativeRms(gk, ck, mask), termsChange = relativeRms(ck, c90, mask);
  check(termsChange >= MIN_CHANGE, `8 terms instead of 200 change the CPU picture by ${(100 * termsChange).toFixed(1)}% (≥ ${100 * MIN_CHANGE}%)`);
  check(ek <= TOLERANCE, `terms=8, rotate 90,0,0: relative RMS ${(100 * ek).toFixed(2)}% against --terms 8`);
  const change = relativeRms(c90, c0, mask);
  check(change >= MIN_CHANGE, `the rotation changes the CPU picture by ${(100 * change).toFixed(1)}% (≥ ${100 * MIN_CHANGE}%)`);
  const changeError = relativeRms(g90, c90, mask, { a: g0, b: c0 });
  check(changeError <= CHANGE_TOLERANCE, `the page's change differs from the CPU's by ${(100 * changeError).toFixed(2)}% of it (≤ ${100 * CHANGE_TOLERANCE}%)`);
  const shot = await shoot('rotate=40,-20,0', 'viewer_haar', { width: 960, height: 540, after: timeLightChanges });
  writeFileSync(`${out}/haar_timing.json`, JSON.stringify(shot.result, null, 1));
  const median = (key) => middle(shot.result.map((c) => c[key]));
  console.log(`light change (median of ${shot.result.length}): ${median('total').toFixed(1)} ms — rotated cube ${median('cube').toFixed(1)}, ` +
    `transform ${median('transform').toFixed(1)}, selection ${median('select').toFixed(1)}, vertices ${median('shade').toFixed(1)}`);
} catch (error) {
  check(false, error.message);
} finally {
  await browser.close();
}
process.exit(failures() === 0 ? 0 : 1);
