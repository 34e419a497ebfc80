// web/glossy.js — view-dependent shading of prt's GLOSSY transfer in the `prt view` page: the
// arithmetic of prt::GlossyRelighter (prt/glossy/relighter.h; docs/GLOSSY.md, "Shading") on the
// GPU, from the payloads of cli/view/glossy_payload.h (docs/VIEWER.md, "Glossy files").
//
// Per vertex v with frame rows (t, b, n) and material q:
//   ωo = (t·d, b·d, n·d), d = eye − p (0 radiance when n·d ≤ 0: the BRDFs are one-sided);
//   y_i = Σ_j M_v,c',i,j L_c,j         (.prtg: the vertex's matrix, c' = c or 0 for grey M)
//   y_i = P_q,0,i + Σ_k w_v,k P_q,k,i  (.prtq: P_q,k = U_q,k · L, computed per frame in
//                                       JavaScript for every cluster: clusterProducts())
//   exit_c = Σ_i b_c,i(ωo) y_c,i,       b from the material's sampled nodes (viewVector()).
// b: a "table" material (isotropic) holds b(θo, 0) at T elevations, θo = t/(T−1)·90°,
// interpolated linearly in θo and rotated about +z by φo (per band the pairs (m, −m) mix by
// cos mφo, sin mφo) — what prt::BrdfProjection's isotropic table does; a "matrix" material
// (anisotropic) holds B with b_c,i(ωo) = Σ_e B_c,i,e y_e(ωo) over the view-side SH y_e of order
// m_v with l + m even (node e = l(l+1)/2 + (m + l)/2) — the library's matrix projection.
// Lighting: channel-major radiance SH (prt-relight.js prepareLighting, windowed then rotated),
// given to the material through prt-relight.js setLighting (its uLight uniform); exposure and
// tone map as prt-relight.js's. The eye is the camera's position at each draw.
//
//   parseGlossy(manifest, transferBuffer, glossyBuffer)   typed views of the payloads
//   viewVector(glossy, material, wo)     b(ωo) at local ωo: Float64Array(3·n²), channel-major
//   localView(glossy, v, position, eye)  ωo of vertex v, normalised (null below the horizon)
//   clusterProducts(glossy, lighting)    the per-frame CPCA products, RGBA float32 texels
//   shadeGlossyVertex(glossy, v, position, lighting, eye)   one vertex on the CPU (tests)
//   createGlossyMaterial(manifest, transferBuffer, glossyBuffer)   the RawShaderMaterial
import * as THREE from 'three';
import { floatTexture, halfTexture, MAX_ORDER, shRecurrenceGlsl, TONE_MAPPED_FRAGMENT_SHADER } from './prt-relight.js';
import { evaluateBasis } from './sh.js';

export const MAX_MATERIALS = 64;
export const MAX_VIEW_ORDER = 16;  // the matrix projections' view-side order (order + 6 by default)
const HALF_PI = Math.PI / 2;

export function parseGlossy(manifest, transferBuffer, glossyBuffer) {
  const g = manifest.glossy;
  const order = manifest.order, n2 = order * order;
  const vertex = g.vertex, brdf = g.brdf;
  const out = {
    form: g.form,
    order,
    n2,
    channels: manifest.channels,
    vertex: { ...vertex, data: new Float32Array(glossyBuffer, vertex.offset, vertex.width * vertex.height * 4) },
    brdf: { ...brdf, data: new Float32Array(glossyBuffer, brdf.offset, brdf.width * brdf.height * 4) },
    materials: brdf.materials,
  };
  if (g.form === 'cpca') {
    const t = manifest.transfer;
    out.cpca = { clusters: t.clusters, vectors: t.vectors, dimension: t.dimension, data: new Float32Array(transferBuffer) };
  } else {
    out.matrices = { ...manifest.transfer, data: new Uint16Array(transferBuffer) };
  }
  return out;
}

// The node's coefficient i (RGB) in glossy.brdf: texel node·n² + i.
function node(glossy, index, i, out, weight) {
  const d = glossy.brdf.data, at = 4 * (index * glossy.n2 + i);
  out[0] += weight * d[at];
  out[1] += weight * d[at + 1];
  out[2] += weight * d[at + 2];
}

export function viewVector(glossy, materialIndex, wo) {
  const n2 = glossy.n2, order = glossy.order;
  const m = glossy.materials[materialIndex];
  const b = new Float64Array(3 * n2);
  const [x, y, z] = wo;
  const rgb = [0, 0, 0];
  if (m.kind === 'matrix') {  // b_c,i = Σ_e B_c,i,e y_e(ωo), e = l(l+1)/2 + (m + l)/2, l + m even
    const mv = m.view_order;
    const basis = evaluateBasis(mv, x, y, z);
    for (let l = 0; l < mv; ++l)
      for (let mm = -l; mm <= l; mm += 2) {
        const e = (l * (l + 1)) / 2 + (mm + l) / 2;
        for (let i = 0; i < n2; ++i) {
          rgb.fill(0);
          node(glossy, m.first_node + e, i, rgb, basis[l * (l + 1) + mm]);
          for (let c = 0; c < 3; ++c) b[c * n2 + i] += rgb[c];
        }
      }
    return b;
  }
  const T = m.elevations;  // 'table': b(θo, 0) linear in θo, then rotated about +z by φo
  const position = (Math.acos(Math.min(z, 1)) / HALF_PI) * (T - 1);
  const t0 = Math.min(Math.floor(position), T - 2);
  const a = position - t0;
  for (let i = 0; i < n2; ++i) {
    rgb.fill(0);
    node(glossy, m.first_node + t0, i, rgb, 1 - a);
    node(glossy, m.first_node + t0 + 1, i, rgb, a);
    for (let c = 0; c < 3; ++c) b[c * n2 + i] = rgb[c];
  }
  const r = Math.hypot(x, y);
  if (r > 0) {
    const c1 = x / r, s1 = y / r;
    let cm = 1, sm = 0;
    for (let mm = 1; mm < order; ++mm) {
      [cm, sm] = [cm * c1 - sm * s1, sm * c1 + cm * s1];
      for (let l = mm; l < order; ++l)
        for (let c = 0; c < 3; ++c) {
          const ip = c * n2 + l * (l + 1) + mm, im = c * n2 + l * (l + 1) - mm;
          const p = b[ip], q = b[im];
          b[ip] = p * cm - q * sm;
          b[im] = p * sm + q * cm;
        }
    }
  }
  return b;
}

// Texel k of vertex v in the vertex texture.
function vertexTexel(glossy, v, k) {
  const at = 4 * (v * glossy.vertex.texels_per_vertex + k);
  return glossy.vertex.data.subarray(at, at + 4);
}

export function localView(glossy, v, position, eye) {
  const d = [eye[0] - position[0], eye[1] - position[1], eye[2] - position[2]];
  const w = [0, 1, 2].map((r) => {
    const t = vertexTexel(glossy, v, r);
    return Math.fround(Math.fround(Math.fround(t[0] * d[0]) + Math.fround(t[1] * d[1])) + Math.fround(t[2] * d[2]));
  });
  const len = Math.hypot(...w);
  if (!(len > 0) || !(w[2] > 0)) return null;
  return [w[0] / len, w[1] / len, Math.min(w[2] / len, 1)];
}

// P_q,k,i (RGB) for every cluster q and k = 0 (the mean) … K, as RGBA float32 texels
// ((q·(K+1) + k)·n² + i), from the lighting (3·n² channel-major). Accumulated in double.
// absolute: Σ_j |U_ij L_j| instead (the scale of the sum's rounding, for tests).
export function clusterProducts(glossy, lighting, out = null, absolute = false) {
  const { clusters, vectors, dimension, data } = glossy.cpca;
  const n2 = glossy.n2, grey = glossy.channels === 1;
  const count = clusters * (vectors + 1) * n2;
  const products = out ?? new Float32Array(4 * count);
  for (let vec = 0; vec < clusters * (vectors + 1); ++vec) {
    const base = vec * dimension;
    for (let i = 0; i < n2; ++i) {
      const at = 4 * (vec * n2 + i);
      for (let c = 0; c < 3; ++c) {
        const row = base + ((grey ? 0 : c) * n2 + i) * n2, light = c * n2;
        let s = 0;
        if (absolute) for (let j = 0; j < n2; ++j) s += Math.abs(data[row + j] * lighting[light + j]);
        else for (let j = 0; j < n2; ++j) s += data[row + j] * lighting[light + j];
        products[at + c] = s;
      }
    }
  }
  return products;
}

// y (3·n², channel-major) of vertex v under `lighting` (or the CPCA products), and with
// `absolute` the same sums of absolute values.
function transferred(glossy, v, lighting, products, absolute) {
  const n2 = glossy.n2, grey = glossy.channels === 1;
  const y = new Float64Array(3 * n2);
  const f = absolute ? Math.abs : (x) => x;
  if (glossy.cpca) {
    const K = glossy.cpca.vectors;
    const ids = [];
    for (let k = 0; k <= K; ++k) ids.push(vertexTexel(glossy, v, 3 + (k >> 2))[k & 3]);
    const q = ids[0];
    for (let i = 0; i < n2; ++i)
      for (let k = 0; k <= K; ++k) {
        const at = 4 * ((q * (K + 1) + k) * n2 + i), w = k === 0 ? 1 : f(ids[k]);
        for (let c = 0; c < 3; ++c) y[c * n2 + i] += w * products[at + c];
      }
    return y;
  }
  const m = glossy.matrices, per = m.texels_per_vertex * 4;
  const base = v * per;
  for (let c = 0; c < 3; ++c)
    for (let i = 0; i < n2; ++i) {
      let s = 0;
      const row = base + ((grey ? 0 : c) * n2 + i) * n2;
      for (let j = 0; j < n2; ++j) s += f(THREE.DataUtils.fromHalfFloat(m.data[row + j]) * lighting[c * n2 + j]);
      y[c * n2 + i] = s;
    }
  return y;
}

// Exit radiance (RGB) of vertex v toward `eye` (`position` its position, `lighting` 3·n²
// channel-major); also `scale`, the same sum over absolute values of every product (the scale
// of its rounding error, for tests). `products`: clusterProducts() of the lighting, plain and
// absolute, for CPCA (computed here when not given).
export function shadeGlossyVertex(glossy, v, position, lighting, eye, products = null) {
  const wo = localView(glossy, v, position, eye);
  if (!wo) return { rgb: [0, 0, 0], scale: [0, 0, 0] };
  const material = vertexTexel(glossy, v, 0)[3];
  const b = viewVector(glossy, material, wo);
  const p = glossy.cpca ? (products ?? [clusterProducts(glossy, lighting), clusterProducts(glossy, lighting, null, true)]) : [null, null];
  const y = transferred(glossy, v, lighting, p[0], false);
  const yAbs = transferred(glossy, v, lighting, p[1], true);
  const n2 = glossy.n2, rgb = [0, 0, 0], scale = [0, 0, 0];
  for (let c = 0; c < 3; ++c)
    for (let i = 0; i < n2; ++i) {
      rgb[c] += b[c * n2 + i] * y[c * n2 + i];
      scale[c] += Math.abs(b[c * n2 + i]) * yAbs[c * n2 + i];
    }
  return { rgb, scale };
}

// K_lm (√2·K_lm for m > 0) of sh.js's basis at l(l+1)/2 + m, m ≥ 0, l < MAX_VIEW_ORDER.
function viewNormalisation() {
  const out = new Float32Array((MAX_VIEW_ORDER * (MAX_VIEW_ORDER + 1)) / 2);
  for (let l = 0; l < MAX_VIEW_ORDER; ++l)
    for (let m = 0; m <= l; ++m) {
      let ratio = 1;
      for (let i = l - m + 1; i <= l + m; ++i) ratio /= i;
      out[(l * (l + 1)) / 2 + m] = Math.sqrt(((2 * l + 1) / (4 * Math.PI)) * ratio) * (m === 0 ? 1 : Math.SQRT2);
    }
  return out;
}

// GLSL written out for the file's order, channels and K (constant indices, no loops over
// coefficients: SwiftShader runs such code several times faster, as prt-relight.js's sum).
function lines(count, f) {
  return Array.from({ length: count }, (_, i) => f(i)).join('\n');
}

// b of a "table" material: the two nodes about θo, then the rotation about +z by φo.
function tableGlsl(order, n2) {
  const rotation = [];
  for (let m = 1; m < order; ++m) {
    rotation.push('    nc = cm * c1 - sm * s1;', '    sm = sm * c1 + cm * s1;', '    cm = nc;');
    for (let l = m; l < order; ++l) {
      const ip = l * (l + 1) + m, im = l * (l + 1) - m;
      rotation.push(`    p = b[${ip}]; q = b[${im}]; b[${ip}] = p * cm - q * sm; b[${im}] = p * sm + q * cm;`);
    }
  }
  return `
  ivec2 p0 = nodeAt(info.y + t0), p1 = nodeAt(info.y + t0 + 1);
  vec3 t;
${lines(n2, (i) => `  t = texelFetch(uBrdf, p0 + ivec2(${i}, 0), 0).rgb; b[${i}] = t + a * (texelFetch(uBrdf, p1 + ivec2(${i}, 0), 0).rgb - t);`)}
  float r = length(wo.xy);
  if (r > 0.0) {
    float c1 = wo.x / r, s1 = wo.y / r, cm = 1.0, sm = 0.0, nc;
    vec3 p, q;
${rotation.join('\n')}
  }`;
}

// b of a "matrix" material: Σ_e y_e(ωo) B_e over the even view-side SH, by the recurrence of
// prt-relight.js's irradiance() (loops: the view order is per material).
const MATRIX_GLSL = `
  for (int i = 0; i < N2; ++i) b[i] = vec3(0.0);
  int M = info.z;${shRecurrenceGlsl('wo', 'MAX_VIEW_ORDER', 'M', `
      if (((l + m) & 1) == 1) continue;
      int kIndex = l * (l + 1) / 2 + m;
      float kq = uViewK[kIndex / 4][kIndex % 4] * q;
      int e = info.y + l * (l + 1) / 2;
      if (m == 0) {
        ivec2 at = nodeAt(e + l / 2);
        for (int i = 0; i < N2; ++i) b[i] += kq * texelFetch(uBrdf, at + ivec2(i, 0), 0).rgb;
      } else {
        ivec2 ap = nodeAt(e + (l + m) / 2), an = nodeAt(e + (l - m) / 2);
        for (int i = 0; i < N2; ++i)
          b[i] += kq * (re * texelFetch(uBrdf, ap + ivec2(i, 0), 0).rgb + im * texelFetch(uBrdf, an + ivec2(i, 0), 0).rgb);
      }`)}`;

// Σ_i b_i ⊙ y_i, y from the CPCA products: y_i = P_q,0,i + Σ_k w_k P_q,k,i.
function cpcaGlsl(n2, K, texelsPerVertex) {
  const weightTexels = Math.ceil((K + 1) / 4);
  const w = (k) => `w${k >> 2}.${'xyzw'[k & 3]}`;
  return `
  vec4 ${lines(weightTexels, (j) => `w${j} = texelFetch(uVertex, vat + ivec2(${3 + j}, 0), 0)`).split('\n').join(', ')};
  int q = int(w0.x + 0.5);
  ivec2 c0 = ivec2((q % uClustersPerRow) * ${(K + 1) * n2}, q / uClustersPerRow);
${lines(n2, (i) => `  sum += b[${i}] * (texelFetch(uProducts, c0 + ivec2(${i}, 0), 0).rgb${lines(K, (k) => ` + ${w(k + 1)} * texelFetch(uProducts, c0 + ivec2(${(k + 1) * n2 + i}, 0), 0).rgb`).split('\n').join('')});`)}`;
}

// Σ_i b_i ⊙ (M L)_i from the vertex's float16 matrix texels (entries (c·n² + i)·n² + j).
function matricesGlsl(n2, channels, texels) {
  const out = ['  ivec2 mat = ivec2((v % uMatricesPerRow) * ' + texels + ', v / uMatricesPerRow);', '  vec4 t;', '  float y;', '  vec3 yy;'];
  const count = channels * n2 * n2;
  for (let f = 0; f < count; ++f) {
    if (f % 4 === 0) out.push(`  t = texelFetch(uMatrices, mat + ivec2(${f / 4}, 0), 0);`);
    const c = Math.floor(f / (n2 * n2)), i = Math.floor(f / n2) % n2, j = f % n2, e = 'xyzw'[f % 4];
    if (channels === 1) {
      out.push(`  yy ${j === 0 ? '=' : '+='} t.${e} * uLight[${j}];`);
      if (j === n2 - 1) out.push(`  sum += b[${i}] * yy;`);
    } else {
      const ch = 'rgb'[c];
      out.push(`  y ${j === 0 ? '=' : '+='} t.${e} * uLight[${j}].${ch};`);
      if (j === n2 - 1) out.push(`  sum.${ch} += b[${i}].${ch} * y;`);
    }
  }
  return out.join('\n');
}

function vertexShader(glossy) {
  const n2 = glossy.n2, K = glossy.cpca ? glossy.cpca.vectors : 0;
  const kinds = new Set(glossy.materials.map((m) => m.kind));
  const texelsPerVertex = glossy.vertex.texels_per_vertex;
  return /* glsl */ `
precision highp float;
precision highp int;
precision highp sampler2D;
#define N2 ${n2}
#define MAX_VIEW_ORDER ${MAX_VIEW_ORDER}
in vec3 position;
in float prtVertex;
uniform mat4 modelViewMatrix;
uniform mat4 projectionMatrix;
uniform vec3 uEye;
uniform vec3 uLight[${MAX_ORDER * MAX_ORDER}];
uniform sampler2D uVertex;      // frames, material, CPCA cluster and weights
uniform int uVertexPerRow;
uniform sampler2D uBrdf;        // the materials' nodes, N2 texels a node, whole nodes a row
uniform int uBrdfNodesPerRow;
uniform ivec4 uMaterial[${MAX_MATERIALS}];  // kind (0 table, 1 matrix), first node, elevations or view order
uniform vec4 uViewK[${(MAX_VIEW_ORDER * (MAX_VIEW_ORDER + 1)) / 8}];  // K_lm (√2 K_lm for m > 0) at l(l+1)/2 + m
uniform sampler2D uMatrices;    // .prtg: float16 matrices, whole vertices a row
uniform int uMatricesPerRow;
uniform sampler2D uProducts;    // .prtq: the per-frame cluster products, whole clusters a row
uniform int uClustersPerRow;
out vec3 vRadiance;

ivec2 nodeAt(int node) { return ivec2((node % uBrdfNodesPerRow) * N2, node / uBrdfNodesPerRow); }

// b(ωo) of material m at unit local wo (as viewVector() in web/glossy.js).
void viewVector(int m, vec3 wo, out vec3 b[N2]) {
  ivec4 info = uMaterial[m];
  if (info.x == 0) {
    float position = acos(min(wo.z, 1.0)) / 1.5707963267948966 * float(info.z - 1);
    int t0 = min(int(position), info.z - 2);
    float a = position - float(t0);
${kinds.has('table') ? tableGlsl(glossy.order, n2) : ''}
    return;
  }
${kinds.has('matrix') ? MATRIX_GLSL : ''}
}

void main() {
  int v = int(prtVertex + 0.5);
  ivec2 vat = ivec2((v % uVertexPerRow) * ${texelsPerVertex}, v / uVertexPerRow);
  vec4 f0 = texelFetch(uVertex, vat, 0);
  vec3 d = uEye - position;
  vec3 wo = vec3(dot(f0.xyz, d), dot(texelFetch(uVertex, vat + ivec2(1, 0), 0).xyz, d), dot(texelFetch(uVertex, vat + ivec2(2, 0), 0).xyz, d));
  float len = length(wo);
  vec3 sum = vec3(0.0);
  if (len > 0.0 && wo.z > 0.0) {
    wo /= len;
    wo.z = min(wo.z, 1.0);
    vec3 b[N2];
    viewVector(int(f0.w + 0.5), wo, b);
${glossy.cpca ? cpcaGlsl(n2, K, texelsPerVertex) : matricesGlsl(n2, glossy.channels, glossy.matrices.texels_per_vertex)}
  }
  vRadiance = sum;
  gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
}
`;
}


// The material of a glossy payload; prt-relight.js's setLighting and setExposure drive it.
// For CPCA the cluster products are recomputed before a draw whenever uLight has changed.
export function createGlossyMaterial(manifest, transferBuffer, glossyBuffer) {
  const glossy = parseGlossy(manifest, transferBuffer, glossyBuffer);
  if (glossy.order > MAX_ORDER) throw new Error(`order ${glossy.order}: the page shades up to order ${MAX_ORDER}`);
  if (glossy.materials.length > MAX_MATERIALS) throw new Error(`${glossy.materials.length} materials: the page shades up to ${MAX_MATERIALS}`);
  const kinds = new Int32Array(4 * MAX_MATERIALS);
  glossy.materials.forEach((m, i) => {
    if (m.kind === 'matrix' && m.view_order > MAX_VIEW_ORDER) throw new Error(`view order ${m.view_order}: the page evaluates up to ${MAX_VIEW_ORDER}`);
    kinds.set(m.kind === 'table' ? [0, m.first_node, m.elevations, 0] : [1, m.first_node, m.view_order, 0], 4 * i);
  });
  const uniforms = {
    uEye: { value: new THREE.Vector3() },
    uLight: { value: new Float32Array(3 * MAX_ORDER * MAX_ORDER) },
    uOrder: { value: glossy.order },
    uMode: { value: 0 },
    uExposure: { value: 0 },
    uVertex: { value: floatTexture(glossy.vertex.data, glossy.vertex.width, glossy.vertex.height) },
    uVertexPerRow: { value: glossy.vertex.vertices_per_row },
    uBrdf: { value: floatTexture(glossy.brdf.data, glossy.brdf.width, glossy.brdf.height) },
    uBrdfNodesPerRow: { value: glossy.brdf.width / glossy.n2 },
    uMaterial: { value: kinds },
    uViewK: { value: viewNormalisation() },
    uMatrices: { value: null },
    uMatricesPerRow: { value: 1 },
    uProducts: { value: null },
    uClustersPerRow: { value: 1 },
  };
  let products = null, lighting = null, lastLight = null;
  if (glossy.cpca) {
    const perCluster = (glossy.cpca.vectors + 1) * glossy.n2;  // texels; whole clusters a row
    if (perCluster > 8192) throw new Error(`${glossy.cpca.vectors} vectors at order ${glossy.order}: a cluster's products exceed a texture row`);
    const perRow = Math.max(1, Math.floor(4096 / perCluster));
    const width = perRow * perCluster, height = Math.ceil(glossy.cpca.clusters / perRow);
    products = new Float32Array(4 * width * height);
    uniforms.uProducts.value = floatTexture(products, width, height);
    uniforms.uClustersPerRow.value = perRow;
    lighting = new Float64Array(3 * glossy.n2);
    lastLight = new Float32Array(3 * MAX_ORDER * MAX_ORDER).fill(NaN);
  } else {
    const m = glossy.matrices;
    uniforms.uMatrices.value = halfTexture(m.data, m.width, m.height);
    uniforms.uMatricesPerRow.value = m.vertices_per_row;
  }
  const material = new THREE.RawShaderMaterial({
    glslVersion: THREE.GLSL3,
    vertexShader: vertexShader(glossy),
    fragmentShader: TONE_MAPPED_FRAGMENT_SHADER,
    side: THREE.DoubleSide,
    uniforms,
  });
  // Before each draw: the eye, and for CPCA the products of a changed lighting.
  // material.userData.fixedEye ([x, y, z]) pins the eye (a view-independent picture, for tests).
  material.onBeforeRender = (renderer, scene, camera) => {
    const fixed = material.userData.fixedEye;
    if (fixed) uniforms.uEye.value.set(...fixed);
    else uniforms.uEye.value.setFromMatrixPosition(camera.matrixWorld);
    if (!glossy.cpca) return;
    const u = uniforms.uLight.value;
    if (u.every((x, i) => x === lastLight[i])) return;
    lastLight.set(u);
    const n2 = glossy.n2;
    for (let c = 0; c < 3; ++c) for (let k = 0; k < n2; ++k) lighting[c * n2 + k] = u[3 * k + c];
    clusterProducts(glossy, lighting, products);
    uniforms.uProducts.value.needsUpdate = true;
  };
  material.userData.glossy = glossy;
  return material;
}
