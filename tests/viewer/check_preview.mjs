// The preview of a large scene (cli/view/view_preview.h, web/preview.js) in headless Chromium:
// the page draws the preview first and then the full frame, and that full frame is the one the
// page draws without a preview (preview=0), so the preview changes when the picture comes, not
// what it is. The preview itself (drawn while the user moves) must look like the full frame:
// relative RMS over the picture within kPreviewRms.
// Usage: node check_preview.mjs URL OUT_DIR
import { readFileSync } from 'node:fs';
import { launchBrowser, makeChecks, openViewer, relativeRms } from './browser.mjs';
import { readPng } from './png.mjs';

const [url, out] = process.argv.slice(2);
const kSameRms = 0.005;    // the full frame with and without the preview: the same draw
const kPreviewRms = 0.06;  // the preview against the full frame (2.1% measured): coarser triangles
const { check, failures } = makeChecks();
const browser = await launchBrowser(undefined, 300000);
try {
  const page = await browser.newPage();
  const load = async (query, name) => {
    await openViewer(page, url, `ui=0${query}`, 640, 360, 240000);
    const state = await page.evaluate(() => {
      const v = window.prtViewer;
      return { preview: v.previewFrameMs, full: v.firstFrameMs, coarse: !!v.coarse,
        previewVertices: v.manifest?.preview?.vertex_count, vertices: v.manifest?.vertex_count };
    });
    await page.screenshot({ path: `${out}/${name}.png` });
    return { ...state, image: readPng(readFileSync(`${out}/${name}.png`)) };
  };
  const withPreview = await load('', 'full_after_preview');
  check(withPreview.preview !== null && withPreview.preview < withPreview.full,
    `the preview (${withPreview.previewVertices} of ${withPreview.vertices} vertices) came first: ${withPreview.preview?.toFixed(0)} ms, full frame ${withPreview.full.toFixed(0)} ms`);
  check(withPreview.previewVertices > 0 && withPreview.previewVertices < withPreview.vertices / 2, 'the preview is coarser than the scene');
  await page.evaluate(() => window.prtViewer.render(window.prtViewer.coarse));
  await page.screenshot({ path: `${out}/preview.png` });
  const preview = readPng(readFileSync(`${out}/preview.png`));
  const without = await load('&preview=0', 'full_without_preview');
  check(without.preview === null && !without.coarse, 'preview=0: no preview');
  const same = relativeRms(withPreview.image.rgb, without.image.rgb);
  check(same <= kSameRms, `full frame after the preview against without it: relative RMS ${(100 * same).toFixed(3)}% (≤ ${100 * kSameRms}%)`);
  const close = relativeRms(preview.rgb, without.image.rgb);
  check(close > 0 && close <= kPreviewRms, `the preview against the full frame: relative RMS ${(100 * close).toFixed(2)}% (> 0, ≤ ${100 * kPreviewRms}%)`);
} finally {
  await browser.close();
}
process.exit(failures() === 0 ? 0 : 1);
