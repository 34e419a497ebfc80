// web/prt-relight.js — relight prt's precomputed radiance transfer in any three.js app.
//
// One module for the `prt view` page and for GLB files written by `prt export-gltf`
// (docs/VIEWER.md, "Using an exported GLB"). Conventions are prt's (docs/CONVENTIONS.md): real
// orthonormal SH without the Condon–Shortley phase, k = l(l+1)+m, glTF's frame; exit radiance
// B_c = Σ_k T_c,k L_c,k (T includes albedo/π when `albedoFolded`, else it is multiplied by the
// vertex albedo); lighting rotated by M means g(ω) = f(Mᵀω), its coefficients rotated, never
// re-projected.
//
//   prepareLighting({order, coefficients, rotation, window})  channel-major radiance SH (3·order²),
//       windowed (web/sh.js windowFactors) then rotated by M (row-major 3×3): what prt relight
//       shades with for `--window NAME --rotate …`.
//   relightVertex(transfer, channels, order, lighting, albedo)   one vertex on the CPU (tests).
//   transferTextureFromGeometry(geometry, prt)   the float16 texture of a GLB's _PRT_SH* attributes.
//   createRelightMaterial(options)   a RawShaderMaterial that shades every vertex in the vertex
//       shader from a float16 RGBA transfer texture (vertex v owns texels v·P … v·P+P−1, P =
//       ⌈channels·order²/4⌉, coefficients in the order c·order² + k), order ≤ 8, with the
//       lighting in uniforms, then exposure, Narkowicz's ACES fit and the sRGB OETF per pixel
//       (relight/tone_map.h), backs of surfaces black (relight/renderer.h).
//   setLighting(material, lighting), setExposure(material, ev), setMode(material, name)
//   setEmitterLight(geometry, responses, colors)   radiosity emitters added to the light
// Modes: 'transfer' (the file), 'unshadowed' (albedo/π · irradiance at the normal, from the
// lighting alone), 'ao' (AO × unshadowed), 'bent' (AO × unshadowed at the bent normal) and
// 'ao-only' (the AO value itself, grey, no exposure or curve). 'ao' and 'bent' need the
// geometry attributes `ao` and `bentNormal`.
import * as THREE from 'three';
import { clampedCosineFactors, rotateCoefficients, windowFactors } from './sh.js';

export const MAX_ORDER = 8;
export const MODES = ['transfer', 'unshadowed', 'ao', 'bent', 'ao-only'];

export function prepareLighting({ order, coefficients, rotation, window = { name: 'none' } }) {
  const n = order * order;
  const h = windowFactors(window.name, order, window.strength ?? 0);
  const windowed = new Float64Array(3 * n);
  for (let c = 0; c < 3; ++c)
    for (let l = 0; l < order; ++l)
      for (let k = l * l; k < (l + 1) * (l + 1); ++k) windowed[c * n + k] = h[l] * coefficients[c * n + k];
  return rotation ? rotateCoefficients(order, rotation, windowed, 3) : windowed;
}

// transfer: channels·order² values (c·order² + k); lighting: 3·order² channel-major.
export function relightVertex(transfer, channels, order, lighting, albedo = [1, 1, 1]) {
  const n = order * order;
  const out = [0, 0, 0];
  for (let c = 0; c < 3; ++c) {
    const t = channels === 1 ? 0 : c * n;
    let sum = 0;
    for (let k = 0; k < n; ++k) sum += transfer[t + k] * lighting[c * n + k];
    out[c] = sum * albedo[c];
  }
  return out;
}

// The texture of prt's layout from a geometry whose attributes `_prt_sh0` … (GLTFLoader's names
// for _PRT_SH0 …, VEC4) hold the transfer. `prt` is the mesh's extras.prt (export-gltf).
export function transferTextureFromGeometry(geometry, prt, maxWidth = 4096) {
  const texelsPerVertex = prt.attribute_count;
  const width = texelsPerVertex * Math.floor(maxWidth / texelsPerVertex);
  const count = geometry.getAttribute('position').count;
  const height = Math.max(1, Math.ceil((count * texelsPerVertex) / width));
  const data = new Uint16Array(width * height * 4);
  for (let j = 0; j < texelsPerVertex; ++j) {
    const attribute = geometry.getAttribute(`_prt_sh${j}`);
    if (!attribute || attribute.itemSize !== 4) throw new Error(`missing VEC4 attribute _PRT_SH${j}`);
    for (let v = 0; v < count; ++v) {
      const at = (v * texelsPerVertex + j) * 4;
      for (let e = 0; e < 4; ++e) data[at + e] = THREE.DataUtils.toHalfFloat(attribute.array[v * 4 + e]);
    }
  }
  return { texture: halfTexture(data, width, height), width, height, texelsPerVertex };
}

// An RGBA data texture read texel by texel (nearest, no mipmaps): float16 (Uint16Array) or
// float32 (Float32Array) texels.
function dataTexture(data, width, height, type) {
  const texture = new THREE.DataTexture(data, width, height, THREE.RGBAFormat, type);
  texture.minFilter = texture.magFilter = THREE.NearestFilter;
  texture.generateMipmaps = false;
  texture.needsUpdate = true;
  return texture;
}
export const halfTexture = (data, width, height) => dataTexture(data, width, height, THREE.HalfFloatType);
export const floatTexture = (data, width, height) => dataTexture(data, width, height, THREE.FloatType);

// GLSL: the loops over m and l (l < `order`, at most `maxOrder`) of the SH recurrence of
// web/sh.js (no Condon–Shortley phase) at the unit vector `dir`; `body` runs for each (l, m)
// with q = P_l^m(dir.z)·(its normalisation left out) and (re, im) = the real and imaginary
// parts of (dir.x + i·dir.y)^m.
export function shRecurrenceGlsl(dir, maxOrder, order, body) {
  return `
  float re = 1.0, im = 0.0, qmm = 1.0;
  for (int m = 0; m < ${maxOrder}; ++m) {
    if (m >= ${order}) break;
    if (m > 0) {
      float r = re * ${dir}.x - im * ${dir}.y;
      im = re * ${dir}.y + im * ${dir}.x;
      re = r;
      qmm *= float(2 * m - 1);
    }
    float qPrev = 0.0, q = qmm;
    for (int l = m; l < ${maxOrder}; ++l) {
      if (l >= ${order}) break;
      if (l > m) {
        float next = l == m + 1 ? ${dir}.z * float(2 * m + 1) * qmm
                                : (float(2 * l - 1) * ${dir}.z * q - float(l + m - 1) * qPrev) / float(l - m);
        qPrev = q;
        q = next;
      }
${body}
    }
  }`;
}

// K_lm (√2·K_lm for m ≠ 0) at k = l(l+1)±m: the normalisation web/sh.js's evaluateBasis uses.
function basisNormalisation() {
  const out = new Float32Array(MAX_ORDER * MAX_ORDER);
  for (let l = 0; l < MAX_ORDER; ++l)
    for (let m = 0; m <= l; ++m) {
      let ratio = 1;
      for (let i = l - m + 1; i <= l + m; ++i) ratio /= i;
      const k = Math.sqrt(((2 * l + 1) / (4 * Math.PI)) * ratio) * (m === 0 ? 1 : Math.SQRT2);
      out[l * (l + 1) + m] = k;
      out[l * (l + 1) - m] = k;
    }
  return out;
}

// The transfer sum written out for one file's order and channel count: one texelFetch per texel
// of the vertex, one multiply-add per coefficient, no loops, divisions or branches (a software
// rasteriser such as SwiftShader runs it several times faster than the loop it replaces). The
// texture is a whole number of vertices wide, so a vertex's texels share a row.
function transferSumGlsl(order, channels, texelsPerVertex) {
  const n = order * order, count = channels * n;
  const lines = [
    'vec3 transferRadiance() {',
    '  int v = int(prtVertex + 0.5);',
    `  ivec2 at = ivec2((v % uVerticesPerRow) * ${texelsPerVertex}, v / uVerticesPerRow);`,
    '  vec3 sum = vec3(0.0);',
    '  vec4 t;',
  ];
  const component = 'xyzw';
  for (let j = 0; j < texelsPerVertex; ++j) {
    lines.push(`  t = texelFetch(uTransfer, at + ivec2(${j}, 0), 0);`);
    for (let e = 0; e < 4 && 4 * j + e < count; ++e) {
      const i = 4 * j + e;
      if (channels === 1) lines.push(`  sum += t.${component[e]} * uLight[${i}];`);
      else lines.push(`  sum.${'rgb'[Math.floor(i / n)]} += t.${component[e]} * uLight[${i % n}].${'rgb'[Math.floor(i / n)]};`);
    }
  }
  lines.push('  return uAlbedoFolded == 1 ? sum : sum * albedo;', '}');
  return lines.join('\n');
}

function vertexShader(order, channels, texelsPerVertex) {
  return /* glsl */ `
precision highp float;
precision highp int;
precision highp sampler2D;
in vec3 position;
in vec3 normal;
in vec3 albedo;
in float ao;
in vec3 bentNormal;
in float prtVertex;
in vec3 emitted;
uniform mat4 modelViewMatrix;
uniform mat4 projectionMatrix;
uniform sampler2D uTransfer;
uniform int uVerticesPerRow, uOrder, uMode, uAlbedoFolded;
uniform vec3 uLight[${MAX_ORDER * MAX_ORDER}];
uniform float uBasisK[${MAX_ORDER * MAX_ORDER}];
uniform float uCosine[${MAX_ORDER}];
out vec3 vRadiance;

${transferSumGlsl(order, channels, texelsPerVertex)}

// E(n) = Σ_l A_l Σ_m L_lm Y_lm(n), Y by the recurrence of web/sh.js (no Condon–Shortley phase).
vec3 irradiance(vec3 n) {
  vec3 e = vec3(0.0);
${shRecurrenceGlsl('n', MAX_ORDER, 'uOrder', `
      int k0 = l * (l + 1);
      if (m == 0) e += uCosine[l] * uBasisK[k0] * q * uLight[k0];
      else e += uCosine[l] * uBasisK[k0 + m] * q * (re * uLight[k0 + m] + im * uLight[k0 - m]);`)}
  return e;
}

void main() {
  const float invPi = 0.31830988618379067;
  if (uMode == 0) vRadiance = transferRadiance();
  else if (uMode == 1) vRadiance = albedo * invPi * irradiance(normalize(normal));
  else if (uMode == 2) vRadiance = ao * albedo * invPi * irradiance(normalize(normal));
  else if (uMode == 3) vRadiance = ao * albedo * invPi * irradiance(normalize(bentNormal));
  else vRadiance = vec3(ao);
  if (uMode != 4) vRadiance += emitted;
  gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
}
`;
}

export const TONE_MAP_GLSL = /* glsl */ `
float prtAces(float x) {
  x = max(x, 0.0);
  return clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}
float prtSrgb(float x) {
  x = clamp(x, 0.0, 1.0);
  return x < 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}
vec3 prtToneMap(vec3 linear, float exposureEv) {
  vec3 x = linear * exp2(exposureEv);
  return vec3(prtSrgb(prtAces(x.r)), prtSrgb(prtAces(x.g)), prtSrgb(prtAces(x.b)));
}
`;

// The fragment shader of the materials that shade per vertex without display modes (glossy.js,
// haar-view.js): vRadiance tone-mapped, backs of surfaces black.
export const TONE_MAPPED_FRAGMENT_SHADER = /* glsl */ `
precision highp float;
in vec3 vRadiance;
uniform float uExposure;
out vec4 outColor;
${TONE_MAP_GLSL}
void main() {
  outColor = vec4(prtToneMap(gl_FrontFacing ? vRadiance : vec3(0.0), uExposure), 1.0);
}
`;

const FRAGMENT_SHADER = /* glsl */ `
precision highp float;
precision highp int;
in vec3 vRadiance;
uniform float uExposure;
uniform int uMode;
out vec4 outColor;
${TONE_MAP_GLSL}
void main() {
  vec3 radiance = gl_FrontFacing ? vRadiance : vec3(0.0);
  if (uMode == 4) outColor = vec4(prtSrgb(radiance.r), prtSrgb(radiance.g), prtSrgb(radiance.b), 1.0);
  else outColor = vec4(prtToneMap(radiance, uExposure), 1.0);
}
`;

// options: { order, channels, albedoFolded, transfer: { texture, width, texelsPerVertex } }
// (width a multiple of texelsPerVertex).
export function createRelightMaterial({ order, channels, albedoFolded, transfer }) {
  if (order > MAX_ORDER) throw new Error(`order ${order}: the shader shades up to order ${MAX_ORDER}`);
  if (transfer.width % transfer.texelsPerVertex !== 0)
    throw new Error(`a transfer texture ${transfer.width} wide does not hold whole vertices of ${transfer.texelsPerVertex} texels`);
  const cosine = new Float32Array(MAX_ORDER);
  cosine.set(clampedCosineFactors(order));
  return new THREE.RawShaderMaterial({
    glslVersion: THREE.GLSL3,
    vertexShader: vertexShader(order, channels, transfer.texelsPerVertex),
    fragmentShader: FRAGMENT_SHADER,
    side: THREE.DoubleSide,
    uniforms: {
      uTransfer: { value: transfer.texture },
      uVerticesPerRow: { value: transfer.width / transfer.texelsPerVertex },
      uOrder: { value: order },
      uMode: { value: 0 },
      uAlbedoFolded: { value: albedoFolded ? 1 : 0 },
      uLight: { value: new Float32Array(3 * MAX_ORDER * MAX_ORDER) },
      uBasisK: { value: basisNormalisation() },
      uCosine: { value: cosine },
      uExposure: { value: 0 },
    },
  });
}

// lighting: 3·order² channel-major (prepareLighting's result).
export function setLighting(material, lighting) {
  const order = material.uniforms.uOrder.value;
  const n = order * order;
  const u = material.uniforms.uLight.value;
  u.fill(0);
  for (let k = 0; k < n; ++k) for (let c = 0; c < 3; ++c) u[3 * k + c] = lighting[c * n + k];
}

export function setExposure(material, ev) {
  material.uniforms.uExposure.value = ev;
}

export function setMode(material, mode) {
  const index = MODES.indexOf(mode);
  if (index < 0) throw new Error(`unknown mode ${mode}`);
  material.uniforms.uMode.value = index;
}

// Attributes the shader reads besides position and normal, filled with neutral values when the
// data has none (albedo 1, AO 1, bent normal = normal), and `prtVertex`, each vertex's index as a
// float (exact below 2^24 vertices): the row of the transfer texture it reads.
export function addDefaultAttributes(geometry) {
  const count = geometry.getAttribute('position').count;
  const index = new Float32Array(count);
  for (let v = 0; v < count; ++v) index[v] = v;
  geometry.setAttribute('prtVertex', new THREE.BufferAttribute(index, 1));
  if (!geometry.getAttribute('albedo'))
    geometry.setAttribute('albedo', new THREE.BufferAttribute(new Float32Array(3 * count).fill(1), 3));
  if (!geometry.getAttribute('ao'))
    geometry.setAttribute('ao', new THREE.BufferAttribute(new Float32Array(count).fill(1), 1));
  if (!geometry.getAttribute('bentNormal')) geometry.setAttribute('bentNormal', geometry.getAttribute('normal'));
  if (!geometry.getAttribute('emitted'))
    geometry.setAttribute('emitted', new THREE.BufferAttribute(new Float32Array(3 * count), 3));
}

// Emitter light (prt relight --emitters): emitted_v = Σ_e c_e ⊙ R_e,v, with responses R laid out
// (e·V + v)·3 + c per unit emission and colours c (3 per emitter), into the geometry's
// `emitted` attribute, which every display but 'ao-only' adds to the radiance.
export function setEmitterLight(geometry, responses, colors) {
  const attribute = geometry.getAttribute('emitted');
  const out = attribute.array, count = out.length / 3, emitters = colors.length / 3;
  out.fill(0);
  for (let e = 0; e < emitters; ++e) {
    const r = colors[3 * e], g = colors[3 * e + 1], b = colors[3 * e + 2];
    if (r === 0 && g === 0 && b === 0) continue;
    const base = 3 * e * count;
    for (let i = 0; i < count; ++i) {
      out[3 * i] += r * responses[base + 3 * i];
      out[3 * i + 1] += g * responses[base + 3 * i + 1];
      out[3 * i + 2] += b * responses[base + 3 * i + 2];
    }
  }
  attribute.needsUpdate = true;
}
