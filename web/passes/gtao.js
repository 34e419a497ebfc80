// web/passes/gtao.js — ground-truth-based ambient occlusion (Jimenez, Wu, Pesce & Jarabo 2016).
// For each pixel, uSlices planes through the view vector V, each at screen angle
// φ = (s + noise)·π/uSlices; in each, a horizon search along ±ω on screen (uSteps samples per
// side, out to uRadius in scene units projected at the pixel's depth) keeps the highest horizon
// cos h = dot(normalize(S − P), V) among samples closer than uRadius. With n the angle of the
// normal projected into the slice (length |n_p|), the horizons clamped to the hemisphere
// (h₁ = n + max(h₁ − n, −π/2), h₂ = n + min(h₂ − n, π/2)), the slice's cosine-weighted visible
// arc integrates in closed form,
//   â = ¼(−cos(2h₁ − n) + cos n + 2h₁ sin n) + ¼(−cos(2h₂ − n) + cos n + 2h₂ sin n),
// and AO = (1/uSlices) Σ |n_p|·â: the cosine-weighted visible fraction that baked AO estimates,
// under GTAO's assumption that what the depth buffer shows is infinitely thick. Samples off
// screen or on background leave the horizon open.
import { aoMaterial } from './ao_common.js';

export function gtaoMaterial(slices, steps) {
  return aoMaterial(
    /* glsl */ `
uniform int uSlices;
uniform int uSteps;
float horizonCos(vec2 uv, vec2 offset, vec3 P, vec3 V, float jitter) {
  float best = -1.0;
  for (int j = 0; j < uSteps; ++j) {
    float t = (float(j) + jitter) / float(uSteps);
    vec2 q = uv + offset * t;
    if (!onScreen(q) || !covered(q)) continue;
    vec3 d = viewPosition(q) - P;
    float l = length(d);
    if (l < 1e-6 * uRadius || l > uRadius) continue;
    best = max(best, dot(d / l, V));
  }
  return best;
}
void main() {
  if (!covered(vUv)) { outColor = vec4(1.0, 1.0, 1.0, 0.0); return; }
  vec3 P = viewPosition(vUv);
  vec3 N = viewNormal(vUv);
  vec3 V = normalize(-P);
  // uRadius in uv units at this depth (x and y scale differently with the aspect).
  vec2 radiusUv = 0.5 * uRadius * vec2(uProj[0][0], uProj[1][1]) / max(-P.z, 1e-6);
  float sliceNoise = tileNoise(0.0), stepNoise = tileNoise(17.0);
  float visible = 0.0;
  for (int s = 0; s < uSlices; ++s) {
    float phi = (float(s) + sliceNoise) * PI / float(uSlices);
    vec2 omega = vec2(cos(phi), sin(phi));
    vec3 dir = vec3(omega, 0.0);
    vec3 orthoDir = dir - dot(dir, V) * V;
    vec3 axis = normalize(cross(dir, V));
    vec3 projN = N - axis * dot(N, axis);
    float projLen = length(projN);
    if (projLen < 1e-6) continue;
    float cosN = clamp(dot(projN, V) / projLen, 0.0, 1.0);
    float n = sign(dot(orthoDir, projN)) * acos(cosN);
    vec2 offset = omega * radiusUv;
    float h2 = acos(horizonCos(vUv, offset, P, V, stepNoise));
    float h1 = -acos(horizonCos(vUv, -offset, P, V, stepNoise));
    h1 = n + max(h1 - n, -0.5 * PI);
    h2 = n + min(h2 - n, 0.5 * PI);
    float sinN = sin(n);
    float arc = 0.25 * (-cos(2.0 * h1 - n) + cosN + 2.0 * h1 * sinN) +
                0.25 * (-cos(2.0 * h2 - n) + cosN + 2.0 * h2 * sinN);
    visible += projLen * arc;
  }
  float ao = clamp(visible / float(uSlices), 0.0, 1.0);
  outColor = vec4(ao, ao, ao, 1.0);
}`,
    { uSlices: { value: Math.max(1, slices | 0) }, uSteps: { value: Math.max(1, steps | 0) } },
  );
}
