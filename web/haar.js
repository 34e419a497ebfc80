// web/haar.js — all-frequency (Haar-wavelet) relighting in JavaScript, the lighting side of
// `prt relight` for Haar files (relight/haar_relight.h) and the sparse product of
// prt/haar/relighter.h. Ng, Ramamoorthi & Hanrahan, "All-Frequency Shadows Using Non-linear
// Wavelet Lighting Approximation", SIGGRAPH 2003, Sec. 4–6. No three.js: it runs under node
// (tests/viewer/check_haar_js.mjs compares it with the C++ library).
//
// Conventions are prt/haar/cube_map.h's and prt/haar/transform.h's: faces +X, −X, +Y, −Y, +Z,
// −Z, N×N each, row-major, row 0 at the top; face point (a, b) ∈ [−1, 1]² looks along
//   +X (1, −b, a)  −X (−1, −b, −a)  +Y (a, 1, −b)  −Y (a, −1, b)  +Z (−a, −b, 1)  −Z (a, −b, −1);
// cube RGB at rgb[3·(face·N² + row·N + col) + c]; wavelet index i = face·N² + q, q in the
// quadtree order of the non-standard 2D Haar transform (coarse to fine); the lighting rotated by
// M (row-major 3×3, web/sh.js rotationFromYawPitchRoll) is g(ω) = f(Mᵀω).
//
// One light change (HaarLight.lighting):
//   1. the rotated cube: M = I → the server's cube, resampled from the map with exact area
//      weighting (prt::resample_to_cube); otherwise each texel averages 4×4 sub-directions ω,
//      each reading the fine cube (2N, at most 128, also the server's) at Mᵀω, nearest texel,
//      weighted by the exact sub-texel solid angle — relight::make_rotated_cube, step for step;
//   2. the forward Haar transform of every face and channel (in double, stored as float);
//   3. the non-linear approximation: the K coefficients of highest area-weighted score
//      w_q · max_c |c| (w_q = Ω_support/s), ties to the lower index (prt::select_nonlinear);
//   4. per vertex, B_v,c = step_v · Σ_kept L̂_i,c · stored_v,i,c, walking the kept terms' vertex
//      lists in index order (prt::shade_index_lists) into float32 accumulators.
// Same arithmetic as the C++ (double where it uses double, float32 where it stores float), so
// results agree to float rounding; the selection agrees exactly on the same coefficients.

export const FACE_COUNT = 6;
export const MAX_CUBE_SIZE = 128;
export const ROTATION_SUBSAMPLES = 4; // per axis, per target texel (relight/haar_relight.h)

// The unit direction of face point (a, b) into out[0..2].
export function cubeFacePointDirection(face, a, b, out) {
  let x, y, z;
  switch (face) {
    case 0: x = 1; y = -b; z = a; break;
    case 1: x = -1; y = -b; z = -a; break;
    case 2: x = a; y = 1; z = -b; break;
    case 3: x = a; y = -1; z = b; break;
    case 4: x = -a; y = -b; z = 1; break;
    default: x = a; y = -b; z = -1; break;
  }
  const inv = 1.0 / Math.sqrt(x * x + y * y + z * z);
  out[0] = x * inv;
  out[1] = y * inv;
  out[2] = z * inv;
  return out;
}

// The texel (face·N² + row·N + col) a direction falls in; −1 for a zero or non-finite direction.
// Ties between axes go to x, then y, then z (prt::direction_to_cube_face_point).
export function directionToCubeTexel(size, x, y, z) {
  if (!Number.isFinite(x) || !Number.isFinite(y) || !Number.isFinite(z)) return -1;
  const ax = Math.abs(x), ay = Math.abs(y), az = Math.abs(z);
  let face, a, b;
  if (ax >= ay && ax >= az) {
    if (ax === 0) return -1;
    face = x > 0 ? 0 : 1;
    a = (x > 0 ? z : -z) / ax;
    b = -y / ax;
  } else if (ay >= az) {
    face = y > 0 ? 2 : 3;
    a = x / ay;
    b = (y > 0 ? -z : z) / ay;
  } else {
    face = z > 0 ? 4 : 5;
    a = (z > 0 ? -x : x) / az;
    b = -y / az;
  }
  const col = Math.min(size - 1, Math.max(0, Math.floor((a + 1.0) * 0.5 * size)));
  const row = Math.min(size - 1, Math.max(0, Math.floor((b + 1.0) * 0.5 * size)));
  return (face * size + row) * size + col;
}

function cornerSolidAngle(a, b) {
  return Math.atan2(a * b, Math.sqrt(a * a + b * b + 1.0));
}

// Exact solid angle of the face rectangle [a0, a1]×[b0, b1].
export function cubeFaceRectSolidAngle(a0, a1, b0, b1) {
  return cornerSolidAngle(a1, b1) - cornerSolidAngle(a0, b1) - cornerSolidAngle(a1, b0) + cornerSolidAngle(a0, b0);
}

// Where coefficient q of an N×N face lives (prt::describe_haar_coefficient).
export function describeHaarCoefficient(size, q) {
  if (q === 0) return { level: 0, band: -1, supportSize: size, supportRow: 0, supportCol: 0 };
  let j = 0;
  while (4 ** (j + 1) <= q) ++j;
  const levelCount = 4 ** j, offset = q - levelCount, side = 2 ** j;
  const position = offset % levelCount, supportSize = size / side;
  return {
    level: j,
    band: Math.floor(offset / levelCount),
    supportSize,
    supportRow: Math.floor(position / side) * supportSize,
    supportCol: (position % side) * supportSize,
  };
}

// Area weights w_q = Ω_support(q)/s, q ∈ [0, N²) (prt::haar_area_weights; same summed table).
export function haarAreaWeights(size) {
  const n = size, step = 2.0 / n;
  const sat = new Float64Array((n + 1) * (n + 1));
  for (let r = 0; r < n; ++r) {
    let rowSum = 0;
    for (let c = 0; c < n; ++c) {
      const a0 = -1.0 + c * step, b0 = -1.0 + r * step;
      rowSum += cubeFaceRectSolidAngle(a0, a0 + step, b0, b0 + step);
      sat[(r + 1) * (n + 1) + c + 1] = sat[r * (n + 1) + c + 1] + rowSum;
    }
  }
  const at = (r, c) => sat[r * (n + 1) + c];
  const weights = new Float64Array(n * n);
  for (let q = 0; q < n * n; ++q) {
    const { supportRow: r0, supportCol: c0, supportSize: s } = describeHaarCoefficient(n, q);
    weights[q] = (at(r0 + s, c0 + s) - at(r0, c0 + s) - at(r0 + s, c0) + at(r0, c0)) / s;
  }
  return weights;
}

// Forward non-standard 2D Haar transform of one face in place (prt::forward_haar_2d): data
// [base + stride·(row·N + col)] on entry, data[base + stride·q] on return; avg: scratch of N²
// doubles.
export function forwardHaar2d(data, size, stride = 1, base = 0, avg = new Float64Array(size * size)) {
  const n2 = size * size;
  for (let t = 0; t < n2; ++t) avg[t] = data[base + t * stride];
  for (let cur = size; cur > 1; cur /= 2) {
    const half = cur / 2, level = half * half;
    for (let y = 0; y < half; ++y) {
      for (let x = 0; x < half; ++x) {
        const top = 2 * y * cur + 2 * x, bottom = top + cur;
        const p00 = avg[top], p01 = avg[top + 1], p10 = avg[bottom], p11 = avg[bottom + 1];
        const pos = y * half + x;
        data[base + (level + pos) * stride] = 0.5 * ((p00 - p01) + (p10 - p11));
        data[base + (2 * level + pos) * stride] = 0.5 * ((p00 + p01) - (p10 + p11));
        data[base + (3 * level + pos) * stride] = 0.5 * ((p00 - p01) - (p10 - p11));
        avg[pos] = 0.5 * ((p00 + p01) + (p10 + p11));
      }
    }
  }
  data[base] = avg[0];
  return data;
}

// The Haar coefficients of an RGB cube (Float32Array 6N²·3, the layout above), a new array.
export function transformCube(rgb, size) {
  const out = Float32Array.from(rgb);
  const avg = new Float64Array(size * size), faceValues = size * size * 3;
  for (let face = 0; face < FACE_COUNT; ++face)
    for (let c = 0; c < 3; ++c) forwardHaar2d(out, size, 3, face * faceValues + c, avg);
  return out;
}

function isIdentity(m) {
  for (let i = 0; i < 9; ++i) if (m[i] !== (i % 4 === 0 ? 1 : 0)) return false;
  return true;
}

// The K terms of highest area-weighted score (k ≤ 0 or ≥ 6N²: all), by ascending index:
// { size, index: Uint32Array, rgb: Float32Array (3 per term) }. `weights`: haarAreaWeights(size).
export function selectNonlinear(wavelets, size, k, weights = haarAreaWeights(size)) {
  const n2 = size * size, total = FACE_COUNT * n2;
  const finite = (v) => (Number.isFinite(v) ? v : 0);
  const keep = k <= 0 || k >= total ? total : Math.floor(k);
  const index = new Uint32Array(keep);
  if (keep === total) {
    for (let i = 0; i < total; ++i) index[i] = i;
  } else {
    const score = new Float64Array(total);
    for (let i = 0; i < total; ++i) {
      const m = Math.max(Math.abs(finite(wavelets[3 * i])), Math.abs(finite(wavelets[3 * i + 1])), Math.abs(finite(wavelets[3 * i + 2])));
      score[i] = weights[i % n2] * m;
    }
    // The k-th highest score; everything above it is kept, then equal scores by ascending index
    // (the strict order "score descending, then index ascending" of the C++).
    const sorted = Float64Array.from(score).sort();
    const threshold = sorted[total - keep];
    let above = 0;
    for (let i = 0; i < total; ++i) if (score[i] > threshold) ++above;
    let ties = keep - above, n = 0;
    for (let i = 0; i < total; ++i) {
      if (score[i] > threshold) index[n++] = i;
      else if (score[i] === threshold && ties > 0) { index[n++] = i; --ties; }
    }
  }
  const rgb = new Float32Array(3 * keep);
  for (let t = 0; t < keep; ++t)
    for (let c = 0; c < 3; ++c) rgb[3 * t + c] = finite(wavelets[3 * index[t] + c]);
  return { size, index, rgb };
}

// The lighting side: the server's cubes (the map at N, and at the fine size for rotations) and the
// tables that do not depend on the rotation.
export class HaarLight {
  // cube: Float32Array 6N²·3 (M = I); fine: Float32Array 6F²·3, F = min(128, 2N).
  constructor(size, cube, fineSize, fine) {
    this.size = size;
    this.cube = cube;
    this.fineSize = fineSize;
    this.fine = fine;
    this.weights = haarAreaWeights(size);
    // Sub-sample directions and exact solid angles of one face (identical for every face up to
    // the direction's face mapping, so directions are stored for all six).
    const S = ROTATION_SUBSAMPLES, texel = 2.0 / size, sub = texel / S, perFace = size * size * S * S;
    this.subWeights = new Float64Array(perFace);
    this.subDirections = new Float64Array(3 * FACE_COUNT * perFace);
    const d = [0, 0, 0];
    for (let face = 0; face < FACE_COUNT; ++face) {
      let j = 0;
      for (let row = 0; row < size; ++row)
        for (let col = 0; col < size; ++col)
          for (let sy = 0; sy < S; ++sy)
            for (let sx = 0; sx < S; ++sx, ++j) {
              const a0 = -1.0 + col * texel + sx * sub, b0 = -1.0 + row * texel + sy * sub;
              cubeFacePointDirection(face, a0 + 0.5 * sub, b0 + 0.5 * sub, d);
              this.subDirections.set(d, 3 * (face * perFace + j));
              if (face === 0) this.subWeights[j] = cubeFaceRectSolidAngle(a0, a0 + sub, b0, b0 + sub);
            }
    }
  }

  // The cube map of the environment rotated by m (a new Float32Array, or the server's cube).
  rotatedCube(m) {
    if (isIdentity(m)) return this.cube;
    const size = this.size, S2 = ROTATION_SUBSAMPLES * ROTATION_SUBSAMPLES, perFace = size * size * S2;
    const out = new Float32Array(FACE_COUNT * size * size * 3);
    const dirs = this.subDirections, w = this.subWeights, fine = this.fine, fineSize = this.fineSize;
    for (let face = 0, texelOut = 0; face < FACE_COUNT; ++face) {
      for (let t = 0; t < size * size; ++t, ++texelOut) {
        let r = 0, g = 0, b = 0, weight = 0;
        for (let s = 0; s < S2; ++s) {
          const j = t * S2 + s, at = 3 * (face * perFace + j);
          const x = dirs[at], y = dirs[at + 1], z = dirs[at + 2];
          const src = directionToCubeTexel(fineSize,
            m[0] * x + m[3] * y + m[6] * z, m[1] * x + m[4] * y + m[7] * z, m[2] * x + m[5] * y + m[8] * z);
          if (src < 0) continue;
          const ws = w[j];
          r += ws * fine[3 * src];
          g += ws * fine[3 * src + 1];
          b += ws * fine[3 * src + 2];
          weight += ws;
        }
        out[3 * texelOut] = weight > 0 ? r / weight : 0;
        out[3 * texelOut + 1] = weight > 0 ? g / weight : 0;
        out[3 * texelOut + 2] = weight > 0 ? b / weight : 0;
      }
    }
    return out;
  }

  // The K-term sparse lighting of the environment rotated by m (k ≤ 0: every term), with the
  // time of each step in ms (timings.cube, .transform, .select).
  lighting(m, k, timings = {}) {
    const t0 = performance.now();
    const cube = this.rotatedCube(m);
    const t1 = performance.now();
    const wavelets = transformCube(cube, this.size);
    const t2 = performance.now();
    const sparse = selectNonlinear(wavelets, this.size, k, this.weights);
    timings.cube = t1 - t0;
    timings.transform = t2 - t1;
    timings.select = performance.now() - t2;
    return sparse;
  }
}

// The sparse transfer, "for each lighting coefficient, the list of vertices that have it":
// { size, channels, vertexCount, offsets (Uint32Array, 6N²+1), vertices (Uint32Array),
//   values (Float32Array, Int16Array or Int8Array; channels per entry), steps (Float32Array, V;
//   null for float32 values) }. Writes B_v,c into out (Float32Array 3V) and returns it.
export function shadeSparse(transfer, lighting, out = new Float32Array(3 * transfer.vertexCount)) {
  const { offsets, vertices, values, steps, channels } = transfer;
  if (lighting.size !== transfer.size)
    throw new Error(`the lighting's cube size ${lighting.size} differs from the transfer's ${transfer.size}`);
  out.fill(0);
  const index = lighting.index, light = lighting.rgb;
  for (let k = 0; k < index.length; ++k) {
    const lr = light[3 * k], lg = light[3 * k + 1], lb = light[3 * k + 2];
    if (lr === 0 && lg === 0 && lb === 0) continue;
    const i = index[k], end = offsets[i + 1];
    if (channels === 1) {
      for (let e = offsets[i]; e < end; ++e) {
        const at = 3 * vertices[e], v = values[e];
        out[at] += lr * v;
        out[at + 1] += lg * v;
        out[at + 2] += lb * v;
      }
    } else {
      for (let e = offsets[i]; e < end; ++e) {
        const at = 3 * vertices[e];
        out[at] += lr * values[3 * e];
        out[at + 1] += lg * values[3 * e + 1];
        out[at + 2] += lb * values[3 * e + 2];
      }
    }
  }
  if (steps)
    for (let v = 0; v < transfer.vertexCount; ++v) {
      const s = steps[v];
      out[3 * v] *= s;
      out[3 * v + 1] *= s;
      out[3 * v + 2] *= s;
    }
  return out;
}
