// web/sh.js against the C++ sh library on the same inputs (sh_reference's JSON): the basis at
// order 8 in 50 directions (poles and axes included), yaw/pitch/roll matrices, rotated
// coefficient vectors at orders 1..8 under five rotations, window band factors and the
// clamped-cosine factors. Both compute in double; the tolerance, 1e-7 relative to the largest
// magnitude of each vector, is float precision (the page hands float32 to the GPU), so a wrong
// sign, index or normalisation anywhere fails by orders of magnitude.
// Usage: node check_sh_js.mjs REFERENCE.json WEB_DIR
import { readFileSync } from 'node:fs';
import { pathToFileURL } from 'node:url';

const [referencePath, webDir] = process.argv.slice(2);
const sh = await import(pathToFileURL(`${webDir}/sh.js`).href);
const reference = JSON.parse(readFileSync(referencePath, 'utf8'));
const TOLERANCE = 1e-7;
let failures = 0, checks = 0;
function compare(what, got, want) {
  const scale = Math.max(1, ...Array.from(want, Math.abs));
  let worst = 0;
  for (let i = 0; i < want.length; ++i) worst = Math.max(worst, Math.abs(got[i] - want[i]) / scale);
  checks += 1;
  if (got.length !== want.length || !(worst <= TOLERANCE)) {
    failures += 1;
    console.log(`FAIL ${what}: worst relative difference ${worst} (lengths ${got.length}, ${want.length})`);
  }
  return worst;
}
let worstBasis = 0, worstRotation = 0;
for (const { direction, values } of reference.basis)
  worstBasis = Math.max(worstBasis, compare(`basis at ${direction}`, sh.evaluateBasis(reference.order, ...direction), values));
for (const r of reference.rotations) {
  const m = sh.rotationFromYawPitchRoll(...r.yaw_pitch_roll);
  compare(`matrix ${r.yaw_pitch_roll}`, m, r.matrix);
  worstRotation = Math.max(worstRotation, compare(`rotation ${r.yaw_pitch_roll} at order ${r.order}`, sh.rotateCoefficients(r.order, m, r.input), r.output));
}
for (const w of reference.windows)
  compare(`window ${w.name} ${w.strength}`, sh.windowFactors(w.name, reference.order, w.strength), w.factors);
compare('clamped cosine', sh.clampedCosineFactors(reference.order), reference.clamped_cosine);
console.log(`${checks - failures}/${checks} agree; worst basis ${worstBasis.toExponential(2)}, worst rotation ${worstRotation.toExponential(2)}`);
process.exit(failures === 0 ? 0 : 1);
