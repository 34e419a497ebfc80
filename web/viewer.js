// web/viewer.js — the `prt view` page: loads the server's payloads (view_payload.h), shades every
// vertex on the GPU with prt-relight.js, draws the environment behind it (background.js), and
// wires the controls. URL parameters (the real-browser test sets them; the controls start from
// them):
//   camera=ex,ey,ez,tx,ty,tz,ux,uy,uz,fov_deg   as prt relight --camera (default: the manifest's,
//                                              relight/auto_camera.h's automatic camera)
//   rotate=yaw,pitch,roll                       as prt relight --rotate (degrees)
//   exposure=EV                                 as prt relight --exposure (default: the
//                                              manifest's automatic exposure)
//   window=none|hanning|lanczos|laplacian|auto  and window_strength=S, as prt relight --window
//                                              (auto: the manifest's choice for the unrotated light)
//   mode=transfer|unshadowed|ao|bent|ao-only|alsoI|PASS  background=0|1   ui=0 (no panel)
//                                              (alsoI: the I-th file of prt view --also, from 0)
//   emitter=NAME=r,g,b (repeatable)             as prt relight --emitter (prt view --emitters)
//   antialias=0                                 one sample a pixel (as prt relight --spp 1)
//   eye=x,y,z                                   glossy files: shade toward this eye, not the camera's
//   terms=K                                     Haar files: lighting terms, as prt relight --terms
//   preview=0                                   no coarse first frame (preview.js) for a large scene
// A large scene is drawn first from its coarse preview (preview.js), then, as soon as the full
// payloads have arrived, in full; window.prtViewer appears after the full frame.
// window.prtViewer exposes the state for tests: ready, firstFrameMs, previewFrameMs (or null),
// timings (ms since navigation), render(), measureFrames(n).
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { createBackground } from './background.js';
import { addDefaultAttributes, createRelightMaterial, halfTexture, MODES, prepareLighting, setEmitterLight, setExposure, setLighting, setMode } from './prt-relight.js';
import { rotationFromYawPitchRoll } from './sh.js';
import { createGlossyMaterial } from './glossy.js';
import { passes } from './passes/index.js';
import { kRefineMs, previewMesh, wantsPreview } from './preview.js';
import { addHaarControls, createHaarView } from './haar-view.js';

const started = performance.now();
const params = new URLSearchParams(location.search);
const status = document.getElementById('status');

function numbers(text, count, name) {
  const values = text.split(',').map(Number);
  if (values.length !== count || values.some((v) => !Number.isFinite(v)))
    throw new Error(`${name}=${text}: expected ${count} numbers`);
  return values;
}

async function fetchBytes(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
  return response.arrayBuffer();
}

function section(buffer, info, Type) {
  return new Type(buffer, info.offset, info.count);
}

// The relit mesh of the full payloads: SH transfer; Haar files through haar-view.js; glossy
// files (glossyBuffer = /api/glossy.bin) through glossy.js.
function fullMesh(manifest, meshBuffer, transferBuffer, glossyBuffer = null) {
  const geometry = buildGeometry(manifest, meshBuffer);
  const terms = params.has('terms') ? numbers(params.get('terms'), 1, 'terms')[0] : undefined;
  const haar = manifest.haar ? createHaarView(manifest, transferBuffer, geometry, terms) : null;
  const material = haar ? haar.material : manifest.glossy ? createGlossyMaterial(manifest, transferBuffer, glossyBuffer) : shMaterial(manifest, transferBuffer, manifest.transfer);
  if (manifest.glossy && params.has('eye')) material.userData.fixedEye = numbers(params.get('eye'), 3, 'eye');
  const mesh = new THREE.Mesh(geometry, material);
  mesh.frustumCulled = false;
  mesh.userData.haar = haar;
  return mesh;
}

// The material of an SH transfer payload (transfer.bin or an also<i>.bin, layout `t`).
function shMaterial(manifest, buffer, t) {
  return createRelightMaterial({
    order: manifest.order,
    channels: manifest.channels,
    albedoFolded: manifest.albedo_folded,
    transfer: { texture: halfTexture(new Uint16Array(buffer), t.width, t.height), width: t.width, texelsPerVertex: t.texels_per_vertex },
  });
}

// The meshes of prt view --also: the same geometry, each with a material reading its file's
// transfer texture (manifest.also[i], buffers[i] = /api/also<i>.bin).
function alsoMeshes(manifest, geometry, buffers) {
  return buffers.map((buffer, i) => {
    const mesh = new THREE.Mesh(geometry, shMaterial(manifest, buffer, manifest.also[i].transfer));
    mesh.frustumCulled = false;
    return mesh;
  });
}

function buildGeometry(manifest, meshBuffer) {
  const s = manifest.mesh.sections;
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(section(meshBuffer, s.positions, Float32Array), 3));
  geometry.setAttribute('normal', new THREE.BufferAttribute(section(meshBuffer, s.normals, Float32Array), 3));
  geometry.setAttribute('albedo', new THREE.BufferAttribute(section(meshBuffer, s.albedo, Float32Array), 3));
  if (s.ao) geometry.setAttribute('ao', new THREE.BufferAttribute(section(meshBuffer, s.ao, Float32Array), 1));
  if (s.bent_normals)
    geometry.setAttribute('bentNormal', new THREE.BufferAttribute(section(meshBuffer, s.bent_normals, Float32Array), 3));
  geometry.setIndex(new THREE.BufferAttribute(section(meshBuffer, s.indices, Uint32Array), 1));
  addDefaultAttributes(geometry);
  geometry.computeBoundingSphere();
  return geometry;
}

function initialState(manifest) {
  const state = {
    rotation: [0, 0, 0],
    exposure: manifest.exposure_ev,
    window: { name: manifest.window.name, strength: manifest.window.strength },
    windowChoice: 'auto',
    mode: 'transfer',
    background: params.get('background') !== '0',
  };
  if (params.has('rotate')) state.rotation = numbers(params.get('rotate'), 3, 'rotate');
  if (params.has('exposure')) state.exposure = numbers(params.get('exposure'), 1, 'exposure')[0];
  if (params.has('window') && params.get('window') !== 'auto') {
    state.windowChoice = params.get('window');
    state.window = { name: state.windowChoice, strength: Number(params.get('window_strength') ?? 0) };
  }
  if (params.has('mode')) state.mode = params.get('mode');
  return state;
}

function makeCamera(manifest, aspect) {
  const c = manifest.camera;
  let [eye, target, up, fov] = [c.eye, c.target, c.up, c.yfov_degrees];
  if (params.has('camera')) {
    const v = numbers(params.get('camera'), 10, 'camera');
    [eye, target, up, fov] = [v.slice(0, 3), v.slice(3, 6), v.slice(6, 9), v[9]];
  }
  const distance = Math.hypot(eye[0] - target[0], eye[1] - target[1], eye[2] - target[2]);
  const camera = new THREE.PerspectiveCamera(fov, aspect);
  setClipPlanes(camera, distance, manifest.radius);
  camera.position.set(...eye);
  camera.up.set(...up);
  camera.lookAt(...target);
  camera.updateMatrixWorld();
  return { camera, target: new THREE.Vector3(...target), distance };
}

// Near and far planes around a mesh of bounding radius `radius` seen from `distance`.
function setClipPlanes(camera, distance, radius) {
  camera.near = Math.max(1e-4 * radius, (distance - 2 * radius) * 0.5);
  camera.far = (distance + 2 * radius) * 2;
  camera.updateProjectionMatrix();
}

async function main() {
  const timings = {};
  const manifest = await (await fetch('/api/manifest.json')).json();
  timings.manifest = performance.now();
  const environmentBytes = fetchBytes(manifest.background.url);
  const previewBuffer = wantsPreview(manifest, params) ? await fetchBytes(manifest.preview.url) : null;
  if (previewBuffer) timings.previewBytes = performance.now();
  // The full payloads, requested once the preview's bytes are in (not to slow their download).
  const urls = [manifest.mesh.url, manifest.transfer.url];
  if (manifest.emitters) urls.push(manifest.emitters.url);
  if (manifest.glossy) urls.push(manifest.glossy.url);
  const fullBytes = Promise.all(urls.map(fetchBytes)).then((buffers) => {
    timings.fullBytes = performance.now();
    return buffers;
  });
  const alsoBytes = Promise.all((manifest.also ?? []).map((a) => fetchBytes(a.transfer.url)));
  const environmentBuffer = await environmentBytes;
  let emittersBuffer = null;
  let mesh;
  if (previewBuffer) {
    mesh = previewMesh(manifest, previewBuffer);
  } else {
    const [meshBuffer, transferBuffer, ...extra] = await fullBytes;
    mesh = fullMesh(manifest, meshBuffer, transferBuffer, manifest.glossy ? extra.at(-1) : null);
    emittersBuffer = manifest.emitters ? extra[0] : null;
  }
  let { geometry, material } = mesh;
  manifest.radius = geometry.boundingSphere.radius;
  const scene = new THREE.Scene();
  scene.add(mesh);
  const b = manifest.background;
  const background = createBackground(new Uint16Array(environmentBuffer), b.width, b.height);

  const canvas = document.getElementById('view');
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: params.get('antialias') !== '0', preserveDrawingBuffer: true });
  renderer.outputColorSpace = THREE.LinearSRGBColorSpace; // the shaders write sRGB-encoded values
  renderer.toneMapping = THREE.NoToneMapping;
  renderer.autoClear = false;
  renderer.setPixelRatio(1);
  renderer.setSize(window.innerWidth, window.innerHeight, false);
  const { camera, target, distance } = makeCamera(manifest, window.innerWidth / window.innerHeight);
  const controls = new OrbitControls(camera, canvas);
  controls.target.copy(target);
  controls.mouseButtons = { LEFT: null, MIDDLE: THREE.MOUSE.DOLLY, RIGHT: THREE.MOUSE.ROTATE };
  controls.update();

  if (params.get('ui') === '0') document.getElementById('panel').style.display = 'none';
  const state = initialState(manifest);
  const haar = mesh.userData.haar ?? null; // Haar files: haar-view.js relights on the CPU
  const context = { THREE, renderer, scene, camera, mesh, geometry, material, manifest, state, background, haar };

  // Draws the frame with `target` (the relit mesh, or the coarse preview while the user moves).
  function render(target = context.mesh) {
    const also = /^also\d+$/.test(state.mode) ? context.also?.[Number(state.mode.slice(4))] : undefined;
    if (also && target === context.mesh) target = also;
    const material = target.material;
    const m = rotationFromYawPitchRoll(...state.rotation);
    const builtIn = MODES.includes(state.mode);
    if (builtIn) setMode(material, state.mode);
    else if (also) setMode(material, 'transfer');
    if (haar) haar.setRotation(m);
    else setLighting(material, prepareLighting({ order: manifest.order, coefficients: manifest.lighting.coefficients, rotation: m, window: state.window }));
    setExposure(material, state.exposure);
    camera.updateMatrixWorld(); // the background reads it before renderer.render() would update it
    background.update(camera, m, state.exposure, state.background);
    renderer.clear();
    const pass = passes.find((p) => p.name === state.mode);
    if (pass) {
      pass.render(context);
    } else {
      renderer.render(background.scene, camera);
      const swap = target !== context.mesh;
      if (swap) scene.remove(context.mesh).add(target);
      renderer.render(scene, camera);
      if (swap) scene.remove(target).add(context.mesh);
    }
  }
  context.render = render;
  // While the user drags or slides, a large scene is drawn from its preview, and in full once
  // the input has rested for kRefineMs (preview.js).
  let coarse = null, refine = null;
  const renderInteractive = () => {
    if (!coarse || state.mode !== 'transfer') return render();
    render(coarse);
    clearTimeout(refine);
    refine = setTimeout(() => render(), kRefineMs);
  };
  controls.addEventListener('change', renderInteractive);
  let previewFrameMs = null;
  if (previewBuffer) {
    render();
    waitForGpu(renderer.getContext());
    timings.previewFrame = performance.now();
    previewFrameMs = timings.previewFrame - started;
    status.textContent = `preview (${manifest.preview.vertex_count.toLocaleString()} of ${manifest.vertex_count.toLocaleString()} vertices) in ${previewFrameMs.toFixed(0)} ms; loading the rest…`;
    const [meshBuffer, transferBuffer] = await fullBytes;
    const full = fullMesh(manifest, meshBuffer, transferBuffer);
    scene.remove(mesh);
    scene.add(full);
    const preview = mesh;
    ({ geometry, material } = full);
    Object.assign(context, { mesh: full, geometry, material });
    manifest.radius = geometry.boundingSphere.radius;
    setClipPlanes(camera, distance, manifest.radius);
    mesh = full;
    coarse = preview;
  }
  context.also = alsoMeshes(manifest, geometry, await alsoBytes);
  if (/^also\d+$/.test(state.mode) && !context.also[Number(state.mode.slice(4))])
    throw new Error(`mode=${state.mode}: prt view was given ${context.also.length} --also file(s)`);
  const emitters = manifest.emitters ? { responses: new Float32Array(emittersBuffer), list: manifest.emitters.emitters } : null;
  if (emitters) {
    state.emitterColors = emitterColors(emitters.list);
    setEmitterLight(geometry, emitters.responses, state.emitterColors);
  }
  for (const pass of passes) pass.init?.(context);

  const ui = setUpControls(manifest, state, renderInteractive, canvas);
  if (emitters) setUpEmitterControls(emitters, state, geometry, render);
  if (haar) addHaarControls(haar, manifest, render);
  window.addEventListener('resize', () => {
    renderer.setSize(window.innerWidth, window.innerHeight, false);
    camera.aspect = window.innerWidth / window.innerHeight;
    camera.updateProjectionMatrix();
    render();
  });
  render();
  waitForGpu(renderer.getContext());
  const firstFrameMs = performance.now() - started;
  const firstFrameSinceNavigationMs = performance.now();
  timings.fullFrame = firstFrameSinceNavigationMs;
  status.textContent = `${manifest.vertex_count.toLocaleString()} vertices, ${manifest.kind} ${manifest.haar ? 'cube' : 'SH order'} ${manifest.order}; ` +
    (previewFrameMs === null ? `first frame ${firstFrameMs.toFixed(0)} ms` : `preview ${previewFrameMs.toFixed(0)} ms, full frame ${firstFrameMs.toFixed(0)} ms`);
  window.prtViewer = {
    ready: true,
    context,
    firstFrameMs,
    firstFrameSinceNavigationMs,
    previewFrameMs,
    previewFrameSinceNavigationMs: timings.previewFrame ?? null,
    timings,
    manifest,
    state,
    render,
    ui,
    coarse, // the preview mesh, drawn while the user moves (null without a preview)
    // Renders n frames, each waited for (waitForGpu), and returns their times in ms; with
    // `target` = coarse, the frames drawn while the user moves.
    measureFrames(n, target = context.mesh) {
      const times = [];
      const gl = renderer.getContext();
      for (let i = 0; i < n; ++i) {
        state.rotation[0] += 1;
        const t0 = performance.now();
        render(target);
        waitForGpu(gl);
        times.push(performance.now() - t0);
      }
      return times;
    },
  };
}

// The emitters' colours: the stored emission, or emitter=NAME=r,g,b (or NAME=v) from the URL.
function emitterColors(list) {
  const colors = new Float64Array(3 * list.length);
  list.forEach((e, i) => colors.set(e.emission, 3 * i));
  for (const spec of params.getAll('emitter')) {
    const at = spec.lastIndexOf('=');
    const i = list.findIndex((e) => e.name === spec.slice(0, at));
    if (at < 0 || i < 0) throw new Error(`emitter=${spec}: no such emitter`);
    const v = spec.slice(at + 1).split(',').map(Number);
    if (!(v.length === 1 || v.length === 3) || v.some((x) => !(x >= 0))) throw new Error(`emitter=${spec}: expected r,g,b ≥ 0`);
    colors.set(v.length === 1 ? [v[0], v[0], v[0]] : v, 3 * i);
  }
  return colors;
}

// One row per emitter: an intensity slider (× the colour, 0..4) and a tint (sRGB picker,
// linearised), over the colour it started with.
function setUpEmitterControls(emitters, state, geometry, render) {
  const panel = document.getElementById('emitters');
  const base = Float64Array.from(state.emitterColors);
  emitters.list.forEach((e, i) => {
    const row = document.createElement('label');
    row.textContent = `${e.name} `;
    const intensity = Object.assign(document.createElement('input'), { type: 'range', min: 0, max: 4, step: 0.05, value: 1 });
    const tint = Object.assign(document.createElement('input'), { type: 'color', value: '#ffffff' });
    const shown = document.createElement('span');
    const update = () => {
      shown.textContent = ` ×${Number(intensity.value).toFixed(2)}`;
      const hex = tint.value;
      const linear = [1, 3, 5].map((k) => {
        const c = parseInt(hex.slice(k, k + 2), 16) / 255;
        return c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4;
      });
      for (let c = 0; c < 3; ++c) state.emitterColors[3 * i + c] = base[3 * i + c] * Number(intensity.value) * linear[c];
      setEmitterLight(geometry, emitters.responses, state.emitterColors);
      render();
    };
    intensity.addEventListener('input', update);
    tint.addEventListener('input', update);
    shown.textContent = ' ×1.00';
    row.append(intensity, shown, tint);
    panel.append(row);
  });
}

// A number for the panel: three significant digits, no trailing zeros (0.0251, 1.91, 12.5).
function shownNumber(value) {
  return Number(value.toPrecision(3)).toString();
}

// Blocks until the GPU has drawn the frame: reading one pixel back waits for it (Chromium's
// gl.finish() returns at once, its GPU process runs on).
function waitForGpu(gl) {
  gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
}

function setUpControls(manifest, state, render, canvas) {
  const exposure = document.getElementById('exposure');
  const exposureText = document.getElementById('exposure-value');
  const windowSelect = document.getElementById('window');
  const strength = document.getElementById('window-strength');
  const mode = document.getElementById('mode');
  const showBackground = document.getElementById('background');
  const showExposure = () => { exposureText.textContent = `${state.exposure >= 0 ? '+' : ''}${state.exposure.toFixed(2)} EV`; };
  exposure.value = state.exposure;
  showExposure();
  exposure.addEventListener('input', () => { state.exposure = Number(exposure.value); showExposure(); render(); });
  windowSelect.value = state.windowChoice;
  strength.value = shownNumber(state.window.strength);
  const applyWindow = () => {
    state.windowChoice = windowSelect.value;
    // auto keeps the manifest's exact strength (the picture prt relight draws); the field shows
    // it rounded, and a strength typed in is used as typed.
    state.window = state.windowChoice === 'auto'
      ? { name: manifest.window.name, strength: manifest.window.strength }
      : { name: state.windowChoice, strength: Number(strength.value) };
    if (state.windowChoice === 'auto') strength.value = shownNumber(manifest.window.strength);
    render();
  };
  windowSelect.addEventListener('change', applyWindow);
  strength.addEventListener('change', applyWindow);
  const available = { transfer: true, unshadowed: !manifest.glossy, ao: !!manifest.mesh.sections.ao, bent: !!manifest.mesh.sections.bent_normals, 'ao-only': !!manifest.mesh.sections.ao };
  const labels = { transfer: `${manifest.kind} (file)`, unshadowed: 'unshadowed (normal)', ao: 'baked AO × unshadowed', bent: 'bent normal × AO', 'ao-only': 'baked AO' };
  for (const name of MODES) {
    if (!available[name] || (manifest.haar && name !== 'transfer')) continue; // Haar: the file only
    mode.add(new Option(labels[name], name));
  }
  (manifest.also ?? []).forEach((a, i) => mode.add(new Option(`${a.kind} (${a.file})`, `also${i}`)));
  for (const pass of passes) mode.add(new Option(pass.label, pass.name));
  mode.value = state.mode;
  mode.addEventListener('change', () => { state.mode = mode.value; render(); });
  showBackground.checked = state.background;
  showBackground.addEventListener('change', () => { state.background = showBackground.checked; render(); });
  // Left drag turns the environment (yaw about +Y, pitch about +X); right drag orbits the camera.
  let drag = null;
  canvas.addEventListener('pointerdown', (e) => {
    if (e.button !== 0) return;
    drag = { x: e.clientX, y: e.clientY, yaw: state.rotation[0], pitch: state.rotation[1] };
    canvas.setPointerCapture(e.pointerId);
  });
  canvas.addEventListener('pointermove', (e) => {
    if (!drag) return;
    state.rotation[0] = drag.yaw + 0.4 * (e.clientX - drag.x);
    state.rotation[1] = Math.max(-90, Math.min(90, drag.pitch + 0.4 * (e.clientY - drag.y)));
    render();
  });
  canvas.addEventListener('pointerup', () => { drag = null; });
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  return { exposure, windowSelect, mode };
}

main().catch((error) => {
  status.textContent = `prt view: ${error.message}`;
  window.prtViewer = { ready: false, error: error.message };
  console.error(error);
});
