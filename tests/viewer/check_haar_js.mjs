// web/haar.js against the C++ library on the same inputs (haar_reference's JSON):
//   1. the rotated 8-cube of a test map under five rotations (the JS resampling of the C++'s
//      16-cube, given the C++'s matrix) against relight::make_rotated_cube;
//   2. the Haar coefficients of the C++'s rotated cube against prt::transform_cube;
//   3. the non-linear selections (K = 1, 7, 50, 200, all) of the C++'s coefficients against
//      prt::select_nonlinear: the same indices and values, exactly;
//   4. the whole chain in JS (rotate, transform, select) against the C++'s selection: the same
//      indices, values within float precision;
//   5. the sparse product of grey and RGB transfer, 8-bit, 16-bit and float32, against
//      prt::HaarRelighter::shade.
// Tolerances: cubes and coefficients 1e-6 of the largest magnitude (both sides sum in double and
// store float; only an ulp of atan2 in a solid-angle weight differs); radiance K·2⁻²⁴ of
// Σ|T̂·L̂| per vertex (the float-accumulation bound of prt/haar/relighter.h for K terms). A wrong
// face mapping, index, sign, weight or step fails by orders of magnitude.
// Usage: node check_haar_js.mjs REFERENCE.json WEB_DIR
import { readFileSync } from 'node:fs';
import { pathToFileURL } from 'node:url';

const [referencePath, webDir] = process.argv.slice(2);
const haar = await import(pathToFileURL(`${webDir}/haar.js`).href);
const reference = JSON.parse(readFileSync(referencePath, 'utf8'));
const TOLERANCE = 1e-6;
let failures = 0, checks = 0;
function check(ok, message) {
  checks += 1;
  if (!ok) {
    failures += 1;
    console.log(`FAIL ${message}`);
  }
}
function worstRelative(got, want) {
  const scale = Math.max(...Array.from(want, Math.abs));
  let worst = got.length === want.length ? 0 : Infinity;
  for (let i = 0; i < want.length; ++i) worst = Math.max(worst, Math.abs(got[i] - want[i]) / scale);
  return worst;
}
function sameArray(a, b) {
  return a.length === b.length && a.every((v, i) => v === b[i]);
}

const { size, fine_size: fineSize } = reference;
const light = new haar.HaarLight(size, Float32Array.from(reference.cube), fineSize, Float32Array.from(reference.fine));
let worstCube = 0, worstWavelets = 0, worstChain = 0;
for (const r of reference.rotations) {
  const name = `rotation ${r.yaw_pitch_roll}`;
  const cube = light.rotatedCube(r.matrix);
  const e1 = worstRelative(cube, r.cube);
  worstCube = Math.max(worstCube, e1);
  check(e1 <= TOLERANCE, `${name}: rotated cube differs by ${e1}`);
  const wavelets = haar.transformCube(Float32Array.from(r.cube), size);
  const e2 = worstRelative(wavelets, r.wavelets);
  worstWavelets = Math.max(worstWavelets, e2);
  check(e2 <= TOLERANCE, `${name}: Haar coefficients differ by ${e2}`);
  for (const { terms, lighting } of r.selections) {
    const js = haar.selectNonlinear(Float32Array.from(r.wavelets), size, terms);
    check(sameArray(js.index, lighting.index) && sameArray(js.rgb, Float32Array.from(lighting.rgb)),
      `${name}, K = ${terms}: selection differs (${js.index.length} against ${lighting.index.length} terms)`);
    const chain = light.lighting(r.matrix, terms);
    const e3 = worstRelative(chain.rgb, lighting.rgb);
    worstChain = Math.max(worstChain, e3);
    check(sameArray(chain.index, lighting.index) && e3 <= TOLERANCE,
      `${name}, K = ${terms}: the JS chain keeps other terms or values (worst ${e3})`);
  }
}

const TYPES = { 8: Int8Array, 16: Int16Array, 32: Float32Array };
let worstShade = 0;
for (const t of reference.transfers) {
  const transfer = {
    size, channels: t.channels, vertexCount: t.vertex_count,
    offsets: Uint32Array.from(t.offsets), vertices: Uint32Array.from(t.vertices),
    values: TYPES[t.bits].from(t.values), steps: t.bits === 32 ? null : Float32Array.from(t.steps),
  };
  for (const s of t.shaded) {
    const lighting = { size, index: Uint32Array.from(s.lighting.index), rgb: Float32Array.from(s.lighting.rgb) };
    const out = haar.shadeSparse(transfer, lighting);
    // Σ|T̂·L̂| per vertex and channel, for the tolerance.
    const magnitude = new Float64Array(3 * t.vertex_count);
    lighting.index.forEach((i, k) => {
      for (let e = transfer.offsets[i]; e < transfer.offsets[i + 1]; ++e) {
        const v = transfer.vertices[e], step = transfer.steps ? transfer.steps[v] : 1;
        for (let c = 0; c < 3; ++c)
          magnitude[3 * v + c] += Math.abs(lighting.rgb[3 * k + c] * step * transfer.values[t.channels === 1 ? e : 3 * e + c]);
      }
    });
    const bound = lighting.index.length * 2 ** -24;
    let worst = 0;
    for (let j = 0; j < out.length; ++j)
      worst = Math.max(worst, Math.abs(out[j] - s.radiance[j]) / Math.max(magnitude[j], 1e-30));
    worstShade = Math.max(worstShade, worst);
    check(worst <= bound && magnitude.some((m) => m > 0),
      `shading ${t.channels} channel(s), ${t.bits}-bit, ${lighting.index.length} terms: ${worst} of Σ|T·L| (bound ${bound})`);
  }
}
console.log(`${checks - failures}/${checks} agree; worst rotated cube ${worstCube.toExponential(2)}, ` +
  `coefficients ${worstWavelets.toExponential(2)}, chain ${worstChain.toExponential(2)}, shading ${worstShade.toExponential(2)} of Σ|T·L|`);
process.exit(failures === 0 && checks > 0 ? 0 : 1);
