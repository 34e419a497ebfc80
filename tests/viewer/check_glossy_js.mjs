// web/glossy.js against the C++ library on the same inputs: the per-vertex exit radiance of a
// glossy file as the page computes it (the payloads of `prt view`, cli/view/glossy_payload.h:
// frames, b(ωo) from the materials' tables or view-side matrices, the matrices or the CPCA
// cluster products) toward an eye point, against `prt relight --csv --eye` of the same file,
// lighting rotation and window none (prt::GlossyRelighter, float kernels).
// Tolerance, per vertex and channel, relative to the scale S = Σ|b_i|·Σ|M_ij L_j| (the same sum
// over absolute values of every product, which bounds the rounding of either side):
//   .prtg: 2⁻¹⁰·S — the page reads the matrices as float16 (relative rounding ≤ 2⁻¹¹ an entry),
//          the library as float32;
//   .prtq: 1e-5·S — both read float32 arrays; the library sums in float (n² + K terms of
//          relative rounding 2⁻²⁴ ≈ 6e-8, and the CSV's 9 digits), the page in double.
// b is the library's: the isotropic tables' nodes and the view-side matrices' entries rounded
// to float32, evaluated in double here and in float there, so any wrong index, sign, frame or
// interpolation fails by orders of magnitude (b is of order 1 against S·1e-5).
// Usage: node check_glossy_js.mjs DIR CSV EYE ROTATE WEB_DIR
//   DIR holds manifest.json, mesh.bin, transfer.bin, glossy.bin (curl'd from prt view);
//   EYE x,y,z; ROTATE yaw,pitch,roll (degrees, as --rotate).
import { readFileSync } from 'node:fs';
import { pathToFileURL } from 'node:url';

const [dir, csvPath, eyeText, rotateText, webDir] = process.argv.slice(2);
const { parseGlossy, shadeGlossyVertex, clusterProducts } = await import(pathToFileURL(`${webDir}/glossy.js`).href);
const { prepareLighting } = await import(pathToFileURL(`${webDir}/prt-relight.js`).href);
const { rotationFromYawPitchRoll } = await import(pathToFileURL(`${webDir}/sh.js`).href);

const buffer = (name) => { const b = readFileSync(`${dir}/${name}`); return b.buffer.slice(b.byteOffset, b.byteOffset + b.byteLength); };
const manifest = JSON.parse(readFileSync(`${dir}/manifest.json`, 'utf8'));
const glossy = parseGlossy(manifest, buffer('transfer.bin'), buffer('glossy.bin'));
const mesh = buffer('mesh.bin');
const s = manifest.mesh.sections.positions;
const positions = new Float32Array(mesh, s.offset, s.count);
const eye = eyeText.split(',').map(Number);
const lighting = prepareLighting({ order: manifest.order, coefficients: manifest.lighting.coefficients,
  rotation: rotationFromYawPitchRoll(...rotateText.split(',').map(Number)), window: { name: 'none' } });
const products = glossy.cpca ? [clusterProducts(glossy, lighting), clusterProducts(glossy, lighting, null, true)] : null;
const rows = readFileSync(csvPath, 'utf8').trim().split('\n').slice(1).map((line) => line.split(',').map(Number));
if (rows.length !== manifest.vertex_count) {
  console.log(`FAIL the CSV has ${rows.length} rows for ${manifest.vertex_count} vertices`);
  process.exit(1);
}
const tolerance = glossy.cpca ? 1e-5 : 2 ** -10;
let worst = 0, failures = 0, lit = 0;
for (let v = 0; v < rows.length; ++v) {
  const { rgb, scale } = shadeGlossyVertex(glossy, v, positions.subarray(3 * v, 3 * v + 3), lighting, eye, products);
  if (scale.some((x) => x > 0)) lit += 1;
  for (let c = 0; c < 3; ++c) {
    const error = Math.abs(rgb[c] - rows[v][4 + c]) / (scale[c] + 1e-12);
    if (!(error <= tolerance)) {
      if (failures < 5) console.log(`FAIL vertex ${v} channel ${c}: page ${rgb[c]}, library ${rows[v][4 + c]}, scale ${scale[c]}`);
      failures += 1;
    }
    worst = Math.max(worst, Math.abs(rgb[c] - rows[v][4 + c]) / (scale[c] + 1e-12));
  }
}
const kinds = glossy.materials.map((m) => m.kind).join(', ');
console.log(`${failures ? 'FAIL' : 'ok  '} ${manifest.kind} order ${manifest.order}, ${manifest.channels} channel(s), materials ${kinds}: ` +
  `${rows.length} vertices (${lit} facing the eye), worst |page − library| / S = ${worst.toExponential(2)} (≤ ${tolerance.toExponential(2)})`);
process.exit(failures === 0 && lit > rows.length / 4 ? 0 : 1);
