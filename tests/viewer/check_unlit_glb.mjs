// Loads a vertex-coloured GLB written by `prt relight --vertex-colors` with three.js's GLTFLoader
// (the loader of the three.js viewer and many web viewers), from an ArrayBuffer, without a DOM,
// and checks what a viewer will show:
//   * every mesh has an unlit material (GLTFLoader turns KHR_materials_unlit into
//     MeshBasicMaterial) with a white base colour and vertex colours switched on;
//   * the colour attribute (COLOR_0) holds, vertex by vertex in file order, the radiance that
//     `prt relight --csv` printed for the same run (float32 written, %.9g printed: equal to
//     within 1e-6 relative), or with --tonemap EV the filmic curve of it (Narkowicz's ACES fit,
//     written out again here from its formula: relative tolerance 1e-5 for float rounding).
// Usage: node check_unlit_glb.mjs FILE.glb FILE.csv [--tonemap EV]
// Exits 0 when every check passes, 1 with a message on the first failure.
import { readFileSync } from 'node:fs';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';

function fail(message) {
  console.error(`check_unlit_glb: ${message}`);
  process.exit(1);
}

const [glbPath, csvPath, flag, evText] = process.argv.slice(2);
if (!glbPath || !csvPath) fail('usage: node check_unlit_glb.mjs FILE.glb FILE.csv [--tonemap EV]');
const tonemapEv = flag === '--tonemap' ? Number(evText) : null;

function aces(x) {
  if (!(x >= 0)) return 0;
  if (x === Infinity) return 1;
  const y = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
  return Math.min(1, Math.max(0, y));
}

const rows = readFileSync(csvPath, 'utf8').trim().split('\n').slice(1);
const expected = rows.map((line) => {
  const f = line.split(',').map(Number);
  const rgb = [f[4], f[5], f[6]];
  return tonemapEv === null ? rgb : rgb.map((x) => aces(Math.fround(x * 2 ** tonemapEv)));
});

const bytes = readFileSync(glbPath);
const buffer = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
const gltf = await new Promise((resolve, reject) => {
  new GLTFLoader().parse(buffer, '', resolve, reject);
}).catch((error) => fail(`GLTFLoader could not parse ${glbPath}: ${error}`));

const meshes = [];
gltf.scene.traverse((object) => {
  if (object.isMesh) meshes.push(object);
});
if (meshes.length === 0) fail(`${glbPath}: no meshes`);

let vertex = 0;
for (const mesh of meshes) {
  const m = mesh.material;
  if (m.type !== 'MeshBasicMaterial') fail(`mesh ${mesh.name}: material is ${m.type}, not unlit`);
  if (m.color.r !== 1 || m.color.g !== 1 || m.color.b !== 1)
    fail(`mesh ${mesh.name}: base colour ${m.color.r},${m.color.g},${m.color.b} is not white`);
  if (m.vertexColors !== true) fail(`mesh ${mesh.name}: vertex colours are off`);
  const color = mesh.geometry.getAttribute('color');
  if (!color) fail(`mesh ${mesh.name}: no COLOR_0`);
  if (color.itemSize !== 3) fail(`mesh ${mesh.name}: COLOR_0 has ${color.itemSize} components`);
  const tolerance = tonemapEv === null ? 1e-6 : 1e-5;
  for (let i = 0; i < color.count; ++i, ++vertex) {
    if (vertex >= expected.length) fail(`more vertices in the GLB than rows in ${csvPath}`);
    const got = [color.getX(i), color.getY(i), color.getZ(i)];
    for (let c = 0; c < 3; ++c) {
      const want = expected[vertex][c];
      if (Math.abs(got[c] - want) > tolerance * Math.max(1, Math.abs(want)))
        fail(`vertex ${vertex} channel ${c}: COLOR_0 ${got[c]}, expected ${want}`);
      if (tonemapEv !== null && !(got[c] >= 0 && got[c] <= 1))
        fail(`vertex ${vertex}: tone-mapped colour ${got[c]} is outside [0, 1]`);
    }
  }
}
if (vertex !== expected.length) fail(`${vertex} vertices in the GLB, ${expected.length} in the CSV`);
console.log(
  `check_unlit_glb: ${meshes.length} meshes unlit (MeshBasicMaterial), white, ${vertex} ` +
    `COLOR_0 values as expected${tonemapEv === null ? '' : ` (tone-mapped at ${tonemapEv} EV)`}`,
);
