// `prt export-gltf`'s GLB, loaded with three.js's GLTFLoader (as a web app loads it), relit by
// web/prt-relight.js, against `prt relight --csv` of the same file and map (--window none, not
// rotated: the lighting stored in the GLB's extras is the unwindowed projection).
//   * every mesh carries extras.prt (order, channels, attribute_count) and its _PRT_SH*
//     attributes as VEC4 (GLTFLoader names them _prt_sh0 …);
//   * relightVertex() on the attributes (float32, as written) gives each vertex's radiance to
//     float precision: |js − csv| ≤ 1e-6·Σ_k|T_k L_k| + 1e-7 per channel (the C++ kernel sums
//     order² float products — its rounding is bounded by order²·2⁻²⁴·Σ|T L| ≤ 4e-6·Σ|T L| at
//     order 8, and the CSV prints 9 significant digits);
//   * the float16 texture that transferTextureFromGeometry() builds for the GPU holds the same
//     coefficients rounded to float16: its radiance agrees within 2⁻¹⁰·Σ|T L| (half precision);
//   * _PRT_AO and _PRT_BENT_NORMAL are there when the file has them (--expect-ao).
// Usage: node check_export_gltf.mjs FILE.glb FILE.csv WEB_DIR [--expect-ao]
import { readFileSync } from 'node:fs';
import { pathToFileURL } from 'node:url';
import * as THREE from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';

const [glbPath, csvPath, webDir, flag] = process.argv.slice(2);
const { prepareLighting, relightVertex, transferTextureFromGeometry } = await import(pathToFileURL(`${webDir}/prt-relight.js`).href);
function fail(message) {
  console.error(`check_export_gltf: ${message}`);
  process.exit(1);
}

const rows = readFileSync(csvPath, 'utf8').trim().split('\n').slice(1).map((line) => line.split(',').map(Number));
const bytes = readFileSync(glbPath);
const gltf = await new Promise((resolve, reject) =>
  new GLTFLoader().parse(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength), '', resolve, reject))
  .catch((error) => fail(`GLTFLoader could not parse ${glbPath}: ${error}`));
const light = gltf.scene.userData.prt?.lighting;
if (!light) fail('the scene has no extras.prt.lighting');
const lighting = prepareLighting({ order: light.order, coefficients: light.coefficients, rotation: null, window: { name: 'none' } });

let vertex = 0, worst = 0, worstHalf = 0;
const meshes = [];
gltf.scene.traverse((o) => { if (o.isMesh) meshes.push(o); });
for (const mesh of meshes) {
  const prt = mesh.userData.prt;
  if (!prt || prt.format !== 'prt-transfer-gltf 1') fail(`mesh ${mesh.name}: no extras.prt`);
  if (prt.order !== light.order) fail(`mesh ${mesh.name}: order ${prt.order}, lighting ${light.order}`);
  const g = mesh.geometry;
  if (flag === '--expect-ao' && (!g.getAttribute('_prt_ao') || g.getAttribute('_prt_bent_normal')?.itemSize !== 3))
    fail(`mesh ${mesh.name}: no _PRT_AO / _PRT_BENT_NORMAL`);
  const n = prt.order * prt.order, perVertex = prt.channels * n;
  const attributes = [];
  for (let j = 0; j < prt.attribute_count; ++j) {
    const a = g.getAttribute(`_prt_sh${j}`);
    if (!a || a.itemSize !== 4) fail(`mesh ${mesh.name}: _PRT_SH${j} is missing or not VEC4`);
    attributes.push(a);
  }
  const texture = transferTextureFromGeometry(g, prt);
  const texels = texture.texture.image.data;
  for (let i = 0; i < g.getAttribute('position').count; ++i, ++vertex) {
    if (vertex >= rows.length) fail('more vertices in the GLB than rows in the CSV');
    const t = new Float64Array(perVertex), h = new Float64Array(perVertex);
    for (let c = 0; c < perVertex; ++c) {
      t[c] = attributes[c >> 2].array[4 * i + (c & 3)];
      h[c] = THREE.DataUtils.fromHalfFloat(texels[4 * i * prt.attribute_count + c]);
    }
    const got = relightVertex(t, prt.channels, prt.order, lighting);
    const half = relightVertex(h, prt.channels, prt.order, lighting);
    for (let c = 0; c < 3; ++c) {
      let bound = 0;
      for (let k = 0; k < n; ++k) bound += Math.abs(t[prt.channels === 1 ? k : c * n + k] * lighting[c * n + k]);
      const want = rows[vertex][4 + c];
      const error = Math.abs(got[c] - want), errorHalf = Math.abs(half[c] - want);
      if (bound > 0) {
        worst = Math.max(worst, error / bound);
        worstHalf = Math.max(worstHalf, errorHalf / bound);
      }
      if (error > 1e-6 * bound + 1e-7) fail(`vertex ${vertex} channel ${c}: ${got[c]}, prt relight ${want}`);
      if (errorHalf > 2 ** -10 * bound + 1e-7) fail(`vertex ${vertex} channel ${c}: float16 texture gives ${half[c]}, prt relight ${want}`);
    }
  }
}
if (vertex !== rows.length) fail(`${vertex} vertices in the GLB, ${rows.length} rows in the CSV`);
console.log(`${vertex} vertices in ${meshes.length} meshes agree with prt relight: worst ${worst.toExponential(2)} (float32 attributes), ${worstHalf.toExponential(2)} (float16 texture) of Σ|T·L|`);
