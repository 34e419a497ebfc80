// What the real-browser checks and benchmarks of `prt view` share (check_browser.mjs,
// check_browser_haar.mjs, check_preview.mjs, bench/viewer/measure_*.mjs): Debian's Chromium,
// headless, with software WebGL (SwiftShader through ANGLE: no GPU on these machines); the page
// loaded and waited for; screenshots; the picture metrics; pass/fail lines.
import { mkdtempSync, readFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import puppeteer from 'puppeteer-core';
import { readPng } from './png.mjs';

// Chromium ($CHROMIUM or /usr/bin/chromium) with a fresh profile under `profileParent`.
export function launchBrowser(profileParent = tmpdir(), protocolTimeout = 600000) {
  return puppeteer.launch({
    executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
    headless: true,
    protocolTimeout,
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync',
      '--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
      `--user-data-dir=${mkdtempSync(`${profileParent}/prt-chromium-`)}`],
  });
}

// Loads URL?QUERY in `page` at width × height and waits for window.prtViewer; throws with the
// page's message when it did not load or reported an error.
export async function openViewer(page, url, query, width, height, timeout = 600000) {
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  await page.setViewport({ width, height });
  await page.goto(`${url}?${query}`, { timeout });
  await page.waitForFunction('window.prtViewer !== undefined', { timeout });
  const state = await page.evaluate(() => ({ ready: window.prtViewer.ready, error: window.prtViewer.error }));
  if (!state.ready) throw new Error(`the page did not load: ${state.error}`);
  if (errors.length) throw new Error(`the page reported: ${errors.join('; ')}`);
}

// shoot(query, name, { width, height, before, after }): a new page at URL?query, `before` run in
// it (awaited; its argument `arg`) before the screenshot OUT/name.png, `after` after it. Returns
// { image (readPng), firstFrameMs, result (what `after` returned) }.
export function makeShooter(browser, url, out, defaultWidth = 640, defaultHeight = 360) {
  return async (query, name, { width = defaultWidth, height = defaultHeight, before = null, arg = null, after = null } = {}) => {
    const page = await browser.newPage();
    await openViewer(page, url, query, width, height, 120000);
    if (before) await page.evaluate(before, arg);
    const path = `${out}/${name}.png`;
    await page.screenshot({ path });
    const firstFrameMs = await page.evaluate(() => window.prtViewer.firstFrameMs);
    const result = after ? await page.evaluate(after) : null;
    await page.close();
    return { image: readPng(readFileSync(path)), firstFrameMs, result };
  };
}

// The object's pixels of a picture drawn without background (background=0): not black, less a
// 1-pixel rim (edges are antialiased differently on the CPU and the GPU).
export function objectMask(black) {
  const { width, height, rgb } = black;
  const lit = (x, y) => rgb[3 * (y * width + x)] + rgb[3 * (y * width + x) + 1] + rgb[3 * (y * width + x) + 2] > 0;
  const mask = new Uint8Array(width * height);
  for (let y = 1; y < height - 1; ++y)
    for (let x = 1; x < width - 1; ++x)
      mask[y * width + x] = lit(x, y) && lit(x - 1, y) && lit(x + 1, y) && lit(x, y - 1) && lit(x, y + 1) ? 1 : 0;
  return mask;
}

export const maskCount = (mask) => mask.reduce((s, m) => s + m, 0);

// √(Σ(a − b)²/Σ b²) over the mask's pixels (every pixel without one) and the three channels of
// two rgb arrays; with `subtract` = { a, b }, of the changes a − subtract.a and b − subtract.b.
export function relativeRms(a, b, mask = null, subtract = null) {
  let num = 0, den = 0;
  for (let i = 0; i < a.length / 3; ++i) {
    if (mask && !mask[i]) continue;
    for (let c = 0; c < 3; ++c) {
      const j = 3 * i + c;
      const x = subtract ? a[j] - subtract.a[j] : a[j];
      const y = subtract ? b[j] - subtract.b[j] : b[j];
      num += (x - y) ** 2;
      den += y * y;
    }
  }
  return Math.sqrt(num / den);
}

// OUT/name.png's rgb (prt relight's renders).
export const readRgb = (out, name) => readPng(readFileSync(`${out}/${name}.png`)).rgb;

export const median = (values) => [...values].sort((a, b) => a - b)[Math.floor(values.length / 2)];

// check(ok, message) prints "ok" or "FAIL" and the message; failures() counts the FAILs.
export function makeChecks() {
  let failures = 0;
  return {
    check(ok, message) {
      console.log(`${ok ? 'ok  ' : 'FAIL'} ${message}`);
      if (!ok) failures += 1;
    },
    failures: () => failures,
  };
}
