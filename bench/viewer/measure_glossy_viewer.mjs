// Frame time of `prt view`'s page on a GLOSSY file in headless Chromium (software WebGL:
// SwiftShader through ANGLE, no GPU on this machine), for docs/BENCHMARKS.md. Loads the page at
// 960×540, reads the first frame's time (since navigation start), then renders N frames each
// waited for by reading a pixel back (viewer.js waitForGpu):
//   light_turning   the light turned by 1° a frame (new SH rotation; for CPCA the cluster
//                   products U·L recomputed in JavaScript before the draw) — the frame time;
//   camera_moving   the light fixed, the camera orbited by 1° a frame (new eye: b(ωo) changes at
//                   every vertex, no products to recompute);
//   background      the mesh hidden;
// and times the CPCA products alone in the page (clusterProducts, median of N calls).
// Prints one JSON line. Usage: node measure_glossy_viewer.mjs URL FRAMES [ROOT]
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

const [url, framesText, root = process.cwd()] = process.argv.slice(2);
// tests/viewer/browser.mjs: Chromium as the viewer's tests launch it (puppeteer-core from there).
const { launchBrowser, median, openViewer } = await import(pathToFileURL(resolve(root, 'tests/viewer/browser.mjs')).href);
const frames = Number(framesText);
const browser = await launchBrowser();
try {
  const page = await browser.newPage();
  await openViewer(page, url, 'ui=0', 960, 540);
  const result = await page.evaluate(async (n) => {
    const v = window.prtViewer;
    const { clusterProducts } = await import('./glossy.js');
    const lightTurning = v.measureFrames(n);
    const { camera, renderer } = v.context;
    const gl = renderer.getContext();
    const cameraMoving = [];
    for (let i = 0; i < n; ++i) {
      const t0 = performance.now();
      const [tx, , tz] = v.manifest.camera.target, c = Math.cos(Math.PI / 180), s = Math.sin(Math.PI / 180);
      const dx = camera.position.x - tx, dz = camera.position.z - tz;
      camera.position.x = tx + c * dx + s * dz;
      camera.position.z = tz - s * dx + c * dz;
      camera.lookAt(...v.manifest.camera.target);
      v.render();
      gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
      cameraMoving.push(performance.now() - t0);
    }
    v.context.mesh.visible = false;
    const background = v.measureFrames(n);
    const glossy = v.context.material.userData.glossy;
    const products = [];
    if (glossy.cpca) {
      const lighting = new Float64Array(3 * glossy.n2).fill(0.5);
      for (let i = 0; i < n; ++i) {
        const t0 = performance.now();
        clusterProducts(glossy, lighting);
        products.push(performance.now() - t0);
      }
    }
    const m = v.manifest;
    return { vertices: m.vertex_count, triangles: m.triangle_count, order: m.order, channels: m.channels, kind: m.kind,
      clusters: m.transfer.clusters ?? null, vectors: m.transfer.vectors ?? null,
      firstFrameMs: v.firstFrameSinceNavigationMs, lightTurning, cameraMoving, background, products };
  }, frames);
  const frame = median(result.lightTurning), empty = median(result.background);
  console.log(JSON.stringify({ kind: result.kind, vertices: result.vertices, triangles: result.triangles, order: result.order,
    channels: result.channels, clusters: result.clusters, vectors: result.vectors,
    first_frame_ms: Math.round(result.firstFrameMs), frame_ms_median_light_turning: +frame.toFixed(1),
    frame_ms_median_camera_moving: +median(result.cameraMoving).toFixed(1), background_only_ms_median: +empty.toFixed(1),
    cpca_products_ms_median: result.products.length ? +median(result.products).toFixed(2) : null,
    mesh_ns_per_vertex: +((1e6 * (frame - empty)) / result.vertices).toFixed(1), frames }));
} finally {
  await browser.close();
}
