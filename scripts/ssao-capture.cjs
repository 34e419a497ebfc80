// scripts/ssao-capture.cjs — drives headless Chromium (Debian's, through puppeteer-core) over the
// ambient-occlusion page of a running `prt view` server (web/ssao.html) and saves, per camera,
// the float32 read-backs of window.prtAO.read(): CAMERA_position.f32, _normal.f32, _ssao.f32,
// _gtao.f32, _baked.f32 (w·h·4 little-endian floats, rows bottom to top).
// `prt report --ssao` runs it and reads the files; it is not meant to be run by hand.
// Usage: node ssao-capture.cjs MODULES_DIR CHROMIUM URL JOB.json OUT_DIR
//   JOB.json: {"width", "height", "radius", "samples", "slices", "steps",
//              "cameras": [{"name", "eye": [x,y,z], "target": [...], "up": [...], "fov"}]}
// Exits 1 with one line on stderr when anything fails.
'use strict';
const fs = require('fs');
const path = require('path');

async function main() {
  const [modules, chromium, url, jobFile, outDir] = process.argv.slice(2);
  const puppeteer = require(path.join(modules, 'puppeteer-core'));
  const job = JSON.parse(fs.readFileSync(jobFile, 'utf8'));
  const browser = await puppeteer.launch({
    executablePath: chromium,
    headless: true,
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
           '--ignore-gpu-blocklist', '--disable-gpu-sandbox'],
  });
  try {
    const page = await browser.newPage();
    const problems = [];
    page.on('pageerror', (e) => problems.push(String(e)));
    page.on('response', (r) => {
      if (r.status() >= 400 && !r.url().endsWith('/favicon.ico'))
        problems.push(`${r.url()}: HTTP ${r.status()}`);
    });
    await page.setViewport({ width: job.width, height: job.height });
    for (const cam of job.cameras) {
      const q = new URLSearchParams({
        w: job.width, h: job.height, radius: job.radius, samples: job.samples,
        slices: job.slices, steps: job.steps, eye: cam.eye.join(','),
        target: cam.target.join(','), up: cam.up.join(','), fov: cam.fov,
      });
      await page.goto(`${url}/ssao.html?${q}`, { waitUntil: 'load' });
      const ok = await page.evaluate(async () => {
        try { await window.prtAO.ready; return ''; } catch (e) { return String(e); }
      });
      if (ok !== '' || problems.length) throw new Error(`the page failed: ${ok || problems[0]}`);
      for (const which of ['position', 'normal', 'ssao', 'gtao', 'baked']) {
        const b64 = await page.evaluate(async (w) => (await window.prtAO.ready).readBase64(w), which);
        fs.writeFileSync(path.join(outDir, `${cam.name}_${which}.f32`), Buffer.from(b64, 'base64'));
      }
    }
  } finally {
    await browser.close();
  }
}

main().catch((e) => {
  process.stderr.write(`ssao-capture: ${String(e.message || e).split('\n')[0]}\n`);
  process.exit(1);
});
