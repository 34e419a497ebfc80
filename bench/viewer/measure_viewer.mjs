// Frame time of `prt view`'s page in headless Chromium (software WebGL: SwiftShader through
// ANGLE, no GPU on this machine), for docs/BENCHMARKS.md. Loads the page at 960×540, reads the
// time of the first frame (since navigation start: page, three.js, the payloads over HTTP, the
// texture upload, the shader compile and one frame), then renders N frames, each waited for
// by reading a pixel back (viewer.js waitForGpu) and with the light turned by 1° (new SH rotation, new uniforms), first with
// the mesh and then with the mesh hidden (the background alone): the difference over the vertex
// count is the cost of the relit mesh per vertex (vertex shader, rasterisation of its
// triangles), and the difference with the 'ao-only' display (the same mesh, the vertex shader
// without the transfer sum) over the vertex count is the cost of the sum itself (its texel
// fetches and multiply-adds). With a preview (scenes above 200k vertices, cli/view/view_preview.h)
// it also gives the time to the preview frame, the page's stage timings and the frame drawn
// from the preview while the user moves. Prints one JSON line.
// Usage: node measure_viewer.mjs URL FRAMES [ROOT]   (ROOT: the repository, for puppeteer-core)
// PRT_VIEW_QUERY=preview=0 (for instance) adds URL parameters.
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

const [url, framesText, root = process.cwd()] = process.argv.slice(2);
// tests/viewer/browser.mjs: Chromium as the viewer's tests launch it (puppeteer-core from there).
const { launchBrowser, median, openViewer } = await import(pathToFileURL(resolve(root, 'tests/viewer/browser.mjs')).href);
const frames = Number(framesText);
const browser = await launchBrowser();
try {
  const page = await browser.newPage();
  await openViewer(page, url, `ui=0${process.env.PRT_VIEW_QUERY ? `&${process.env.PRT_VIEW_QUERY}` : ''}`, 960, 540);
  const result = await page.evaluate((n) => {
    const v = window.prtViewer;
    const withMesh = v.measureFrames(n);
    const moving = v.coarse ? v.measureFrames(n, v.coarse) : null;  // the preview, while moving
    v.state.mode = 'ao-only';  // the vertex shader without the transfer sum
    const plain = v.measureFrames(n);
    v.state.mode = 'transfer';
    v.context.mesh.visible = false;
    const background = v.measureFrames(n);
    return { vertices: v.manifest.vertex_count, triangles: v.manifest.triangle_count, order: v.manifest.order, channels: v.manifest.channels,
      firstFrameMs: v.firstFrameSinceNavigationMs, previewFrameMs: v.previewFrameSinceNavigationMs, timings: v.timings,
      previewVertices: v.manifest.preview?.vertex_count ?? null, moving, withMesh, plain, background };
  }, frames);
  const frame = median(result.withMesh), plain = median(result.plain), empty = median(result.background);
  console.log(JSON.stringify({ vertices: result.vertices, triangles: result.triangles, order: result.order, channels: result.channels,
    first_frame_ms: Math.round(result.firstFrameMs),
    preview_frame_ms: result.previewFrameMs === null ? null : Math.round(result.previewFrameMs),
    timings_ms: Object.fromEntries(Object.entries(result.timings ?? {}).map(([k, t]) => [k, Math.round(t)])), frame_ms_median: +frame.toFixed(1), background_only_ms_median: +empty.toFixed(1),
    ao_only_ms_median: +plain.toFixed(1),
    preview_vertices: result.previewVertices, moving_frame_ms_median: result.moving ? +median(result.moving).toFixed(1) : null,
    mesh_ns_per_vertex: +((1e6 * (frame - empty)) / result.vertices).toFixed(1),
    transfer_sum_ns_per_vertex: +((1e6 * (frame - plain)) / result.vertices).toFixed(1), frames }));
} finally {
  await browser.close();
}
