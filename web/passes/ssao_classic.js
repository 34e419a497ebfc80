// web/passes/ssao_classic.js — classic screen-space ambient occlusion (Mittring 2007, Crytek; in
// the normal-oriented hemisphere form of Filion & McNaughton 2008 / Chapman's tutorial):
//   - uSamples points of a fixed kernel inside the unit hemisphere around +z (denser near the
//     centre: length scaled by lerp(0.1, 1, (i/n)²)), rotated per pixel about the normal by the
//     4×4 noise tile, scaled by uRadius (scene units) around the pixel's view-space position P;
//   - each sample point S is projected into the depth (position) buffer; it counts as occluded
//     when the surface seen there is in front of S by more than a small bias;
//   - range check: an occluder much farther from P than uRadius fades out,
//     smoothstep(0, 1, uRadius / |P.z − z_buffer|);
//   - AO = 1 − occluded/uSamples (1 = open). Samples projected off screen or onto background
//     count as open. The 4×4 blur (ao_common.js) removes the tile noise.
// This estimates the occluded fraction of a hemisphere *volume*, not the cosine-weighted
// visible fraction of directions that baked AO is: docs/SSAO.md measures the difference.
import * as THREE from 'three';
import { aoMaterial } from './ao_common.js';

export const kMaxClassicSamples = 64;

// The classic kernel: a fixed pseudo-random sequence (xorshift32, seed 1) so every run and
// every machine draws the same points.
export function classicKernel(count) {
  let state = 1;
  const random = () => {
    state ^= state << 13;
    state ^= state >>> 17;
    state ^= state << 5;
    return (state >>> 0) / 4294967296;
  };
  const kernel = [];
  for (let i = 0; i < kMaxClassicSamples; ++i) {
    const v = new THREE.Vector3(random() * 2 - 1, random() * 2 - 1, random());
    v.normalize().multiplyScalar(random());
    const s = i / count;
    v.multiplyScalar(0.1 + 0.9 * s * s);
    kernel.push(v);
  }
  return kernel;
}

export function classicSsaoMaterial(samples) {
  const n = Math.max(1, Math.min(kMaxClassicSamples, samples | 0));
  return aoMaterial(
    /* glsl */ `
uniform vec3 uKernel[${kMaxClassicSamples}];
uniform int uSamples;
void main() {
  if (!covered(vUv)) { outColor = vec4(1.0, 1.0, 1.0, 0.0); return; }
  vec3 P = viewPosition(vUv);
  vec3 N = viewNormal(vUv);
  float a = tileNoise(0.0) * 2.0 * PI;
  vec3 r = vec3(cos(a), sin(a), 0.0);
  if (abs(dot(r, N)) > 0.99) r = vec3(0.0, 0.0, 1.0);
  vec3 T = normalize(r - N * dot(r, N));
  vec3 B = cross(N, T);
  float bias = 0.01 * uRadius;
  float occluded = 0.0;
  for (int i = 0; i < uSamples; ++i) {
    vec3 k = uKernel[i];
    vec3 S = P + (T * k.x + B * k.y + N * k.z) * uRadius;
    vec2 uv = project(S);
    if (!onScreen(uv) || !covered(uv)) continue;
    float z = viewPosition(uv).z;
    float range = smoothstep(0.0, 1.0, uRadius / abs(P.z - z));
    occluded += (z >= S.z + bias ? 1.0 : 0.0) * range;
  }
  float ao = 1.0 - occluded / float(uSamples);
  outColor = vec4(ao, ao, ao, 1.0);
}`,
    { uKernel: { value: classicKernel(n) }, uSamples: { value: n } },
  );
}
