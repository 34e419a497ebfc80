// web/haar-view.js — the `prt view` page's side of Haar-wavelet files (cli/view/haar_payload.h):
// the sparse transfer and the cube maps from transfer.bin, the lighting of each rotation
// computed on the CPU in JavaScript (web/haar.js: resample the rotated map into the cube,
// Haar-transform it, keep the K largest area-weighted terms, sparse dot product per vertex —
// Ng, Ramamoorthi & Hanrahan 2003 did the same on the CPU), and a material that draws the
// per-vertex radiance it uploads, with the exposure, tone curve and back faces of
// web/prt-relight.js (relight/tone_map.h, relight/renderer.h).
//
//   createHaarView(manifest, transferBuffer, geometry, terms) → { material, setRotation(m),
//       setTerms(k), terms, lastChange, lighting, radiance, onChange }
// setRotation(m) recomputes only when m or the term count changed; lastChange holds the times
// (ms) of the last change: cube, transform, select, shade (the upload happens at the next draw),
// total, the number of terms kept and of transfer entries their lists hold (entries).
//   addHaarControls(view, manifest, render)   the panel's term count and timing line.
import * as THREE from 'three';
import { TONE_MAPPED_FRAGMENT_SHADER } from './prt-relight.js';
import { HaarLight, shadeSparse } from './haar.js';

const TYPES = { uint32: Uint32Array, int16: Int16Array, int8: Int8Array, float32: Float32Array };

function section(buffer, info) {
  const Type = TYPES[info.type];
  if (!Type) throw new Error(`transfer.bin: unknown section type ${info.type}`);
  return new Type(buffer, info.offset, info.count);
}

const VERTEX_SHADER = /* glsl */ `
precision highp float;
in vec3 position;
in vec3 albedo;
in vec3 haarRadiance;
uniform mat4 modelViewMatrix;
uniform mat4 projectionMatrix;
uniform int uAlbedoFolded;
out vec3 vRadiance;
void main() {
  vRadiance = uAlbedoFolded == 1 ? haarRadiance : haarRadiance * albedo;
  gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
}
`;


export function createHaarView(manifest, transferBuffer, geometry, terms) {
  const h = manifest.haar, s = h.sections;
  const transfer = {
    size: h.cube_size,
    channels: h.channels,
    vertexCount: manifest.vertex_count,
    offsets: section(transferBuffer, s.offsets),
    vertices: section(transferBuffer, s.vertices),
    values: section(transferBuffer, s.values),
    steps: h.quantization_bits === 32 ? null : section(transferBuffer, s.steps),
  };
  const light = new HaarLight(h.cube_size, section(transferBuffer, s.cube), h.fine_cube_size, section(transferBuffer, s.fine_cube));
  const radiance = new THREE.BufferAttribute(new Float32Array(3 * manifest.vertex_count), 3);
  radiance.setUsage(THREE.DynamicDrawUsage);
  geometry.setAttribute('haarRadiance', radiance);
  const material = new THREE.RawShaderMaterial({
    glslVersion: THREE.GLSL3,
    vertexShader: VERTEX_SHADER,
    fragmentShader: TONE_MAPPED_FRAGMENT_SHADER,
    side: THREE.DoubleSide,
    uniforms: {
      uAlbedoFolded: { value: manifest.albedo_folded ? 1 : 0 },
      uExposure: { value: 0 },
      uMode: { value: 0 }, // setMode() of prt-relight.js writes it; only 'transfer' is offered
    },
  });
  const view = {
    material,
    terms: terms ?? h.default_terms,
    lastChange: null,
    lighting: null,
    key: '',
    setTerms(k) { view.terms = k; },
    setRotation(m) {
      const key = `${Array.from(m).join(',')};${view.terms}`;
      if (key === view.key) return false;
      const t0 = performance.now(), times = {};
      view.lighting = light.lighting(m, view.terms, times);
      const t1 = performance.now();
      shadeSparse(transfer, view.lighting, radiance.array);
      const t2 = performance.now();
      radiance.needsUpdate = true;
      view.key = key;
      let walked = 0; // Σ over the kept terms of their list lengths: the sum's work
      for (const i of view.lighting.index) walked += transfer.offsets[i + 1] - transfer.offsets[i];
      view.lastChange = { ...times, shade: t2 - t1, terms: view.lighting.index.length, entries: walked, total: t2 - t0 };
      view.onChange?.();
      return true;
    },
    radiance: radiance.array,
  };
  return view;
}

// The panel's Haar controls: the term count K (terms=K in the URL sets it at load) and the time
// of the last light change. Replaces the de-ringing window's row, which SH files alone use.
export function addHaarControls(view, manifest, render) {
  const windowRow = document.getElementById('window')?.closest('label');
  if (windowRow) windowRow.style.display = 'none';
  const total = 6 * manifest.haar.cube_size ** 2;
  const row = document.createElement('label');
  row.textContent = 'lighting terms K ';
  const input = Object.assign(document.createElement('input'), { type: 'number', min: 0, max: total, step: 1, value: view.terms });
  input.title = `non-linear approximation: the K largest area-weighted wavelet terms of the ${total} (0: all)`;
  const timing = document.createElement('div');
  timing.className = 'hint';
  const show = () => {
    const c = view.lastChange;
    if (c) timing.textContent = `light change ${c.total.toFixed(1)} ms: cube ${c.cube.toFixed(1)}, wavelets ${c.transform.toFixed(1)}, ` +
      `selection ${c.select.toFixed(1)} (${c.terms} terms), vertices ${c.shade.toFixed(1)}`;
  };
  input.addEventListener('change', () => {
    const k = Math.max(0, Math.min(total, Math.round(Number(input.value)) || 0));
    input.value = k;
    view.setTerms(k);
    render();
  });
  row.append(input);
  const anchor = windowRow ?? document.getElementById('mode')?.closest('label');
  anchor?.after(row, timing);
  view.onChange = show;
  show();
}
