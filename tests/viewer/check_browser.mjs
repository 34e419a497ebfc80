// The real-browser test of `prt view`: Debian's Chromium, headless, driven by puppeteer-core,
// loads the viewer that run_browser_check.sh started and compares its pictures with
// `prt relight`'s renders of the same camera, rotation, window and exposure.
//   1. defaults: the page as it opens (camera, exposure and window from the manifest, i.e. the
//      rules prt relight applies when given none) against `prt relight` with no options;
//   2. rotate=0,0,0 and rotate=90,0,0 at a fixed exposure (the manifest's) and window none,
//      against prt relight --rotate … --exposure … --window none: each within the tolerance, and
//      the change between the two (GPU rotated − GPU unrotated) against the CPU's change.
// The object's pixels: where the page, drawn without background (background=0), is not black,
// minus a 1-pixel rim (edges are antialiased differently: 3×3 samples a pixel on the CPU, MSAA
// on the GPU). Compared values are the 8-bit display values of both PNGs. Relative RMS =
// √(Σ(gpu − cpu)² / Σ cpu²) over those pixels and the three channels.
// Tolerances: 3% for each picture (the GPU shades from float16 transfer and float32 lighting,
// the CPU from float32 transfer and double lighting, and the page's sky is a 512×256 resampling;
// measured 1.4–1.7% on the demo, docs/VIEWER.md); the change must be at least 10% of the picture's
// RMS (the rotation does change the image), and the GPU's change may differ from the CPU's by
// at most 10% of the CPU's.
// With `emitters` (a room lit by its lamps, prt view --emitters): the page at the stored emitter
// colours and at emitter=lamp=2,1,0.5 against prt relight --emitters (--emitter …), same
// tolerance; one sample a pixel on both sides (antialias=0, --spp 1), as the room's emitting
// patches make hard edges inside the object that the two antialiasing schemes draw apart.
// With `glossy CAMERA_A CAMERA_B`: a glossy file, see checkGlossy() below.
// With `also`: prt view shadowed.prt --also interreflected.prt, see checkAlso() below.
// Usage: node check_browser.mjs URL OUT_DIR [emitters | glossy CAMERA_A CAMERA_B]   (OUT_DIR holds cpu_default.png,
// cpu_r0.png, cpu_r90.png — or cpu_emitters.png, cpu_lamp.png — and receives the screenshots;
// exit 0 when every check passes).
import { readFileSync } from 'node:fs';
import { launchBrowser, makeChecks, makeShooter, maskCount, objectMask, readRgb, relativeRms } from './browser.mjs';

const [url, out, emitterCase] = process.argv.slice(2);
const WIDTH = 640, HEIGHT = 360;
const TOLERANCE = 0.03, MIN_CHANGE = 0.10, CHANGE_TOLERANCE = 0.10, MIN_VIEW_CHANGE = 0.06, MIN_ALSO_CHANGE = 0.05;
const { check, failures } = makeChecks();
const browser = await launchBrowser(out);
const shoot = makeShooter(browser, url, out, WIDTH, HEIGHT);
const cpu = (name) => ({ rgb: readRgb(out, name) });

async function checkEmitters() {
  const exposure = JSON.parse(readFileSync(`${out}/manifest.json`, 'utf8')).exposure_ev;
  const fixed = `ui=0&exposure=${exposure}&window=none&antialias=0`;
  const mask = objectMask((await shoot(`${fixed}&background=0`, 'gpu_mask')).image);
  const count = maskCount(mask);
  check(count > 0.2 * WIDTH * HEIGHT, `the room covers ${count} pixels of ${WIDTH * HEIGHT}`);
  const stored = relativeRms((await shoot(fixed, 'gpu_emitters')).image.rgb, cpu('cpu_emitters').rgb, mask);
  check(stored <= TOLERANCE, `emitters at their stored colours: relative RMS ${(100 * stored).toFixed(2)}% against prt relight --emitters`);
  const lamp = relativeRms((await shoot(`${fixed}&emitter=lamp=2,1,0.5`, 'gpu_lamp')).image.rgb, cpu('cpu_lamp').rgb, mask);
  check(lamp <= TOLERANCE, `emitter=lamp=2,1,0.5: relative RMS ${(100 * lamp).toFixed(2)}% against prt relight --emitter lamp=2,1,0.5`);
  const change = relativeRms(cpu('cpu_lamp').rgb, cpu('cpu_emitters').rgb, mask);
  check(change >= MIN_CHANGE, `recolouring the lamp changes the CPU picture by ${(100 * change).toFixed(1)}%`);
  if (JSON.parse(readFileSync(`${out}/manifest.json`, 'utf8')).also) await checkEmittersAlso(fixed, mask);
}

// prt view room.prt --also room_ir.prt --emitters: the emitters' sliders moved as a user moves
// them (SLIDERS: lamp intensity ×0.5; panel intensity ×3, tint #ff0000, i.e. linear (1, 0, 0)),
// then the interreflected display (mode=also0) against prt relight of the --also file with the
// same emitter colours (cpu_sliders_interreflected.png) within TOLERANCE, and the shadowed
// display (the file) against its own render; the two displays must differ by MIN_ALSO_CHANGE.
const SLIDERS = { lamp: { intensity: 0.5, tint: '#ffffff' }, panel: { intensity: 3, tint: '#ff0000' } };
function moveSliders(sliders) {
  for (const row of document.querySelectorAll('#emitters label')) {
    const setting = sliders[row.firstChild.textContent.trim()];
    if (!setting) throw new Error(`no slider setting for emitter ${row.textContent}`);
    const [intensity, tint] = row.querySelectorAll('input');
    intensity.value = setting.intensity;
    intensity.dispatchEvent(new Event('input'));
    tint.value = setting.tint;
    tint.dispatchEvent(new Event('input'));
  }
}
async function checkEmittersAlso(fixed, mask) {
  const moved = { before: moveSliders, arg: SLIDERS };
  const inter = (await shoot(`${fixed}&mode=also0`, 'gpu_sliders_interreflected', moved)).image.rgb;
  const shadowed = (await shoot(`${fixed}&mode=transfer`, 'gpu_sliders_shadowed', moved)).image.rgb;
  const e1 = relativeRms(inter, cpu('cpu_sliders_interreflected').rgb, mask);
  check(e1 <= TOLERANCE, `sliders set, interreflected (mode=also0): relative RMS ${(100 * e1).toFixed(2)}% against prt relight of the --also file with the same --emitter colours`);
  const e0 = relativeRms(shadowed, cpu('cpu_sliders_shadowed').rgb, mask);
  check(e0 <= TOLERANCE, `sliders set, shadowed (the file): relative RMS ${(100 * e0).toFixed(2)}% against prt relight`);
  const apart = relativeRms(inter, shadowed, mask);
  check(apart >= MIN_ALSO_CHANGE, `with the sliders set, the interreflected display differs from the shadowed one by ${(100 * apart).toFixed(1)}% (≥ ${100 * MIN_ALSO_CHANGE}%)`);
  const moves = relativeRms(cpu('cpu_sliders_interreflected').rgb, cpu('cpu_emitters_interreflected').rgb, mask);
  check(moves >= MIN_CHANGE, `the slider settings change prt relight's interreflected picture by ${(100 * moves).toFixed(1)}% (≥ ${100 * MIN_CHANGE}%)`);
}

// A glossy file (glossy, CAMERA_A, CAMERA_B): view-dependent shading. The defaults; then at
// camera A and camera B (the same light turned by 30°, fixed exposure, window none) against
// prt relight --camera …; then view dependence: the page at camera B shading toward A's eye
// (eye=…, what a view-independent picture would show) must differ from prt relight's B by more
// than MIN_VIEW_CHANGE, and the change the page makes when the eye moves from A to B must match
// the CPU's (the GPU's error at B relative to the size of that change: ≤ CHANGE_TOLERANCE).
async function checkGlossy(cameraA, cameraB) {
  const manifest = JSON.parse(readFileSync(`${out}/manifest.json`, 'utf8'));
  const fixed = `ui=0&exposure=${manifest.exposure_ev}&window=none&rotate=30,0,0`;
  const maskA = objectMask((await shoot(`${fixed}&camera=${cameraA}&background=0`, 'gpu_mask_a')).image);
  const maskB = objectMask((await shoot(`${fixed}&camera=${cameraB}&background=0`, 'gpu_mask_b')).image);
  const count = maskCount(maskB);
  check(count > 0.2 * WIDTH * HEIGHT, `the scene covers ${count} pixels of ${WIDTH * HEIGHT} at camera B`);
  const e0 = relativeRms((await shoot('ui=0', 'gpu_default')).image.rgb, cpu('cpu_default').rgb, maskA);
  check(e0 <= TOLERANCE, `${manifest.kind} defaults: relative RMS ${(100 * e0).toFixed(2)}% against prt relight (≤ ${100 * TOLERANCE}%)`);
  const eA = relativeRms((await shoot(`${fixed}&camera=${cameraA}`, 'gpu_a')).image.rgb, cpu('cpu_a').rgb, maskA);
  check(eA <= TOLERANCE, `camera A, rotate 30,0,0: relative RMS ${(100 * eA).toFixed(2)}%`);
  const gB = (await shoot(`${fixed}&camera=${cameraB}`, 'gpu_b')).image.rgb, cB = cpu('cpu_b').rgb;
  const eB = relativeRms(gB, cB, maskB);
  check(eB <= TOLERANCE, `camera B: relative RMS ${(100 * eB).toFixed(2)}%`);
  const eyeA = cameraA.split(',').slice(0, 3).join(',');
  const pinned = (await shoot(`${fixed}&camera=${cameraB}&eye=${eyeA}`, 'gpu_b_eye_a')).image.rgb;
  const viewChange = relativeRms(pinned, cB, maskB);
  check(viewChange >= MIN_VIEW_CHANGE, `camera B shaded toward A's eye differs from prt relight's B by ${(100 * viewChange).toFixed(1)}% (≥ ${100 * MIN_VIEW_CHANGE}%: the shading depends on the view)`);
  const changeError = relativeRms(gB, cB, maskB, { a: pinned, b: pinned });
  check(changeError <= CHANGE_TOLERANCE, `the page's change from eye A to eye B differs from the CPU's by ${(100 * changeError).toFixed(1)}% of it (≤ ${100 * CHANGE_TOLERANCE}%)`);
  await shoot(`camera=${cameraB}`, 'viewer_glossy', { width: 960, height: 540 });  // with the panel, for docs/images
}

// prt view shadowed.prt --also interreflected.prt: the file (mode=transfer) and the extra display
// (mode=also0), at rotate=30,0,0, FILE's exposure and window none, each against prt relight of
// its file (cpu_shadowed.png, cpu_interreflected.png) within TOLERANCE; the two displays must
// differ by at least MIN_ALSO_CHANGE and interreflection must brighten the picture.
async function checkAlso() {
  const manifest = JSON.parse(readFileSync(`${out}/manifest.json`, 'utf8'));
  check(manifest.also?.length === 1 && manifest.also[0].kind === 'interreflected' && manifest.also[0].file === 'interreflected.prt',
    `the manifest lists the --also file: ${JSON.stringify(manifest.also?.map((a) => [a.kind, a.file]))}`);
  const fixed = `ui=0&exposure=${manifest.exposure_ev}&window=none&rotate=30,0,0`;
  const mask = objectMask((await shoot(`${fixed}&background=0`, 'gpu_mask')).image);
  const shadowed = (await shoot(`${fixed}&mode=transfer`, 'gpu_shadowed')).image.rgb;
  const inter = (await shoot(`${fixed}&mode=also0`, 'gpu_interreflected')).image.rgb;
  const e0 = relativeRms(shadowed, cpu('cpu_shadowed').rgb, mask);
  check(e0 <= TOLERANCE, `shadowed (the file): relative RMS ${(100 * e0).toFixed(2)}% against prt relight`);
  const e1 = relativeRms(inter, cpu('cpu_interreflected').rgb, mask);
  check(e1 <= TOLERANCE, `interreflected (mode=also0): relative RMS ${(100 * e1).toFixed(2)}% against prt relight of the --also file`);
  const change = relativeRms(inter, shadowed, mask);
  let sumInter = 0, sumShadowed = 0;
  for (let i = 0; i < mask.length; ++i) if (mask[i]) for (let c = 0; c < 3; ++c) { sumInter += inter[3 * i + c]; sumShadowed += shadowed[3 * i + c]; }
  check(change >= MIN_ALSO_CHANGE && sumInter > sumShadowed,
    `the two displays differ by ${(100 * change).toFixed(1)}% (≥ ${100 * MIN_ALSO_CHANGE}%), interreflected ${(100 * (sumInter / sumShadowed - 1)).toFixed(1)}% brighter`);
  await shoot('mode=also0', 'viewer_also', { width: 960, height: 540 });  // with the panel: the display's label
}

// The demo: the defaults, then rotate=0,0,0 and rotate=90,0,0 and the change between them.
async function checkDemo() {
  const exposure = JSON.parse(readFileSync(`${out}/manifest.json`, 'utf8')).exposure_ev;
  const fixed = `ui=0&exposure=${exposure}&window=none`;
  const mask = objectMask((await shoot(`${fixed}&background=0`, 'gpu_mask')).image);
  const count = maskCount(mask);
  check(count > 0.2 * WIDTH * HEIGHT, `the object covers ${count} pixels of ${WIDTH * HEIGHT}`);
  const defaults = await shoot('ui=0', 'gpu_default');
  const e0 = relativeRms(defaults.image.rgb, cpu('cpu_default').rgb, mask);
  check(e0 <= TOLERANCE, `defaults (camera, exposure, window of the manifest): relative RMS ${(100 * e0).toFixed(2)}% against prt relight (≤ ${100 * TOLERANCE}%)`);
  const g0 = (await shoot(`${fixed}&rotate=0,0,0`, 'gpu_r0')).image.rgb;
  const g90 = (await shoot(`${fixed}&rotate=90,0,0`, 'gpu_r90')).image.rgb;
  const c0 = cpu('cpu_r0').rgb, c90 = cpu('cpu_r90').rgb;
  const e1 = relativeRms(g0, c0, mask), e2 = relativeRms(g90, c90, mask);
  check(e1 <= TOLERANCE, `rotate 0,0,0: relative RMS ${(100 * e1).toFixed(2)}%`);
  check(e2 <= TOLERANCE, `rotate 90,0,0: relative RMS ${(100 * e2).toFixed(2)}%`);
  const change = relativeRms(c90, c0, mask);
  check(change >= MIN_CHANGE, `the rotation changes the CPU picture by ${(100 * change).toFixed(1)}% (≥ ${100 * MIN_CHANGE}%)`);
  const changeError = relativeRms(g90, c90, mask, { a: g0, b: c0 });
  check(changeError <= CHANGE_TOLERANCE, `the GPU's change differs from the CPU's by ${(100 * changeError).toFixed(2)}% of it (≤ ${100 * CHANGE_TOLERANCE}%)`);
  const shot = await shoot('', 'viewer', { width: 960, height: 540 });
  console.log(`first frame ${shot.firstFrameMs.toFixed(0)} ms after the page started (software WebGL)`);
}

const cases = { also: checkAlso, emitters: checkEmitters, glossy: () => checkGlossy(process.argv[5], process.argv[6]) };
try {
  await (cases[emitterCase] ?? checkDemo)();
} catch (error) {
  check(false, error.message);
} finally {
  await browser.close();
}
process.exit(failures() === 0 ? 0 : 1);
