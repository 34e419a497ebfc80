// Time per light change of `prt view` on a Haar file (measure_haar_view.sh starts the server):
// headless Chromium (software WebGL), page at 960×540, the light turned 7° of yaw a change, each
// change timed in the page (web/haar-view.js lastChange: rotated cube, Haar transform, selection,
// sparse sum) and with the frame drawn and waited for (a pixel read back). Prints one JSON line
// of medians (ms) and saves a screenshot to OUT/haar_view.png.
// Usage: node measure_haar_view.mjs URL CHANGES TERMS REPOSITORY_ROOT OUT
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

const [url, changes, terms, root, out] = process.argv.slice(2);
// tests/viewer/browser.mjs: Chromium as the viewer's tests launch it (puppeteer-core from there).
const { launchBrowser, openViewer } = await import(pathToFileURL(resolve(root, 'tests/viewer/browser.mjs')).href);
const browser = await launchBrowser(out);
try {
  const page = await browser.newPage();
  await openViewer(page, url, `terms=${terms}`, 960, 540);
  const result = await page.evaluate((n) => {
    const { context, state, render, firstFrameMs } = window.prtViewer;
    const gl = context.renderer.getContext();
    const rows = [];
    for (let i = 0; i < n; ++i) {
      state.rotation[0] += 7;
      const t0 = performance.now();
      render();
      gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
      rows.push({ ...context.haar.lastChange, frame: performance.now() - t0 });
    }
    const median = (k) => rows.map((r) => r[k]).sort((a, b) => a - b)[rows.length >> 1];
    const keys = ['total', 'cube', 'transform', 'select', 'shade', 'frame', 'entries', 'terms'];
    return { firstFrameMs, vertices: context.manifest.vertex_count, cube: context.manifest.haar.cube_size,
      stored_entries: context.manifest.haar.entries, changes: n,
      median: Object.fromEntries(keys.map((k) => [k, Math.round(100 * median(k)) / 100])) };
  }, Number(changes));
  await page.screenshot({ path: `${out}/haar_view.png` });
  console.log(JSON.stringify(result));
} finally {
  await browser.close();
}
