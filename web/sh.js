// web/sh.js — spherical harmonics for the page and for prt-relight.js, in prt's conventions
// (docs/CONVENTIONS.md, sh/basis.h): real, orthonormal SH without the Condon–Shortley phase,
// order n = bands 0..n−1, index k = l(l+1)+m, unit vectors (x, y, z) in the scene frame (glTF:
// +Y up) with the polar axis +z. Pure ES module, no three.js: it runs in the browser and in node
// (tests/viewer/check_sh_js.mjs compares it with the C++ library on the same inputs).
//
//   evaluateBasis(order, x, y, z)        → Float64Array(order²) of Y_k(x, y, z)
//   rotationFromYawPitchRoll(y, p, r)     → row-major 3×3 M = Ry(yaw)·Rx(pitch)·Rz(roll), degrees
//                                            (sh::rotation_from_yaw_pitch_roll)
//   rotateCoefficients(order, M, input)   → the coefficients of g(ω) = f(Mᵀω) (sh/rotation.h):
//                                            Ivanic & Ruedenberg's recurrence (J. Phys. Chem.
//                                            1996, 1998 corrections) with the sign of V for m < 0
//                                            corrected as in sh/src/rotation.cpp
//   windowFactors(name, order, strength)  → per-band factors h_l of sh/window.h (strength ≤ 0:
//                                            the window's default)
//   clampedCosineFactors(order)           → A_l, so that irradiance E = Σ A_l L_lm Y_lm
// Everything computes in double (JavaScript numbers); the page hands float32 to the GPU.

export function evaluateBasis(order, x, y, z) {
  const out = new Float64Array(order * order);
  // Q_lm: the associated Legendre polynomial divided by sin^m θ, without (−1)^m; then
  // Y_l0 = K_l0 Q_l0, Y_l±m = √2 K_lm Q_lm · Re/Im (x + iy)^m (no division by sin θ, no atan2).
  let re = 1, im = 0; // (x + iy)^m
  let qmm = 1; // (2m − 1)!!
  for (let m = 0; m < order; ++m) {
    if (m > 0) {
      const r = re * x - im * y;
      im = re * y + im * x;
      re = r;
      qmm *= 2 * m - 1;
    }
    let qPrev = 0, q = qmm;
    for (let l = m; l < order; ++l) {
      if (l > m) {
        const next = l === m + 1 ? z * (2 * m + 1) * qmm : ((2 * l - 1) * z * q - (l + m - 1) * qPrev) / (l - m);
        qPrev = q;
        q = next;
      }
      const k = normalisation(l, m);
      if (m === 0) {
        out[l * (l + 1)] = k * q;
      } else {
        out[l * (l + 1) + m] = Math.SQRT2 * k * q * re;
        out[l * (l + 1) - m] = Math.SQRT2 * k * q * im;
      }
    }
  }
  return out;
}

// K_lm = √((2l+1)/4π · (l−m)!/(l+m)!), by a product (no factorial overflow at these orders).
function normalisation(l, m) {
  let ratio = 1;
  for (let i = l - m + 1; i <= l + m; ++i) ratio /= i;
  return Math.sqrt(((2 * l + 1) / (4 * Math.PI)) * ratio);
}

export function rotationFromYawPitchRoll(yawDeg, pitchDeg, rollDeg) {
  const d = Math.PI / 180;
  const cy = Math.cos(yawDeg * d), sy = Math.sin(yawDeg * d);
  const cp = Math.cos(pitchDeg * d), sp = Math.sin(pitchDeg * d);
  const cr = Math.cos(rollDeg * d), sr = Math.sin(rollDeg * d);
  const a = [cr, -sr, 0, cp * sr, cp * cr, -sp, sp * sr, sp * cr, cp]; // Rx·Rz
  return [cy * a[0] + sy * a[6], cy * a[1] + sy * a[7], cy * a[2] + sy * a[8], a[3], a[4], a[5],
    -sy * a[0] + cy * a[6], -sy * a[1] + cy * a[7], -sy * a[2] + cy * a[8]];
}

export function multiplyRotations(a, b) {
  const r = new Array(9).fill(0);
  for (let i = 0; i < 3; ++i)
    for (let j = 0; j < 3; ++j)
      for (let k = 0; k < 3; ++k) r[3 * i + j] += a[3 * i + k] * b[3 * k + j];
  return r;
}

// Row terms of band l, row m: P(i, a, ·) of band l − 1 with their weights (sh/src/rotation.cpp).
function rowTerms(l, m) {
  const terms = [];
  const add = (i, a, w) => { if (w !== 0) terms.push([i, a, w]); };
  const am = Math.abs(m);
  const d0 = m === 0 ? 1 : 0;
  const u = Math.sqrt((l + m) * (l - m));
  const v = 0.5 * Math.sqrt((1 + d0) * (l + am - 1) * (l + am)) * (1 - 2 * d0);
  const w = -0.5 * Math.sqrt((l - am - 1) * (l - am)) * (1 - d0);
  add(0, m, u);
  if (m === 0) {
    add(1, 1, v);
    add(-1, -1, v);
  } else if (m > 0) {
    const d1 = m === 1 ? 1 : 0;
    add(1, m - 1, v * Math.sqrt(1 + d1));
    add(-1, -m + 1, -v * (1 - d1));
    add(1, m + 1, w);
    add(-1, -m - 1, w);
  } else {
    const d1 = m === -1 ? 1 : 0;
    add(1, m + 1, v * (1 - d1));
    add(-1, -m - 1, v * Math.sqrt(1 + d1));
    add(1, m - 1, w);
    add(-1, -m + 1, -w);
  }
  return terms;
}

// The band matrices of bands 0..order−1 for M: an array of row-major (2l+1)² Float64Arrays.
export function rotationBands(order, M) {
  const bands = [Float64Array.of(1)];
  if (order < 2) return bands;
  const axis = [1, 2, 0]; // band 1 is M with rows and columns (y, z, x)
  const r = new Float64Array(9);
  for (let i = 0; i < 3; ++i) for (let j = 0; j < 3; ++j) r[3 * i + j] = M[3 * axis[i] + axis[j]];
  bands.push(r);
  const R = (i, j) => r[(i + 1) * 3 + (j + 1)];
  for (let l = 2; l < order; ++l) {
    const s = 2 * l + 1, ps = 2 * l - 1, prev = bands[l - 1];
    const out = new Float64Array(s * s);
    const invD = (n) => 1 / Math.sqrt(n === l || n === -l ? 2 * l * (2 * l - 1) : (l + n) * (l - n));
    for (let m = -l; m <= l; ++m) {
      let first = 0, last = 0;
      const interior = new Float64Array(ps);
      for (const [i, a, w] of rowTerms(l, m)) {
        const p = (a + l - 1) * ps; // row a of band l − 1
        const c = w * R(i, 0), c1 = w * R(i, 1), cm1 = w * R(i, -1);
        last += c1 * prev[p + ps - 1] - cm1 * prev[p];
        first += c1 * prev[p] + cm1 * prev[p + ps - 1];
        for (let n = 0; n < ps; ++n) interior[n] += c * prev[p + n];
      }
      const row = (m + l) * s;
      out[row] = first * invD(-l);
      out[row + s - 1] = last * invD(l);
      for (let n = 0; n < ps; ++n) out[row + n + 1] = interior[n] * invD(n - l + 1);
    }
    bands.push(out);
  }
  return bands;
}

// out = R(M)·input for `channels` channel-major blocks of order² coefficients.
export function rotateCoefficients(order, M, input, channels = 1) {
  const bands = rotationBands(order, M);
  const n = order * order;
  const out = new Float64Array(channels * n);
  for (let c = 0; c < channels; ++c)
    for (let l = 0; l < order; ++l) {
      const s = 2 * l + 1, base = c * n + l * l, b = bands[l];
      for (let i = 0; i < s; ++i) {
        let sum = 0;
        for (let j = 0; j < s; ++j) sum += b[i * s + j] * input[base + j];
        out[base + i] = sum;
      }
    }
  return out;
}

export function defaultWindowStrength(name, order) {
  if (name === 'hanning') return order;
  if (name === 'lanczos') return 1;
  if (name === 'laplacian') return order < 2 ? 0 : 1 / ((order - 1) ** 2 * order ** 2);
  return 0;
}

export function windowFactors(name, order, strength) {
  const h = new Float64Array(order).fill(1);
  if (!(strength > 0) || !Number.isFinite(strength)) strength = defaultWindowStrength(name, order);
  for (let l = 1; l < order; ++l) {
    if (name === 'hanning') h[l] = l < strength ? 0.5 * (1 + Math.cos((Math.PI * l) / strength)) : 0;
    else if (name === 'lanczos') {
      const x = (Math.PI * l) / order;
      h[l] = Math.pow(Math.sin(x) / x, strength);
    } else if (name === 'laplacian') {
      const ll1 = l * (l + 1);
      h[l] = 1 / (1 + strength * ll1 * ll1);
    } else if (name !== 'none') throw new Error(`unknown window ${name}`);
  }
  return h;
}

// A_l of the clamped cosine max(cos θ, 0): π, 2π/3, then 2π·(−1)^(l/2+1)·(l−1)!! / ((l+2)(l−1)·l!!)
// for even l, 0 for odd l > 1 (Ramamoorthi & Hanrahan 2001).
export function clampedCosineFactors(order) {
  const a = new Float64Array(order);
  for (let l = 0; l < order; ++l) {
    if (l === 0) a[l] = Math.PI;
    else if (l === 1) a[l] = (2 * Math.PI) / 3;
    else if (l % 2 === 1) a[l] = 0;
    else {
      let ratio = 1; // (l−1)!! / l!!
      for (let i = 1; i <= l; ++i) ratio *= i % 2 === 1 ? i : 1 / i;
      a[l] = (2 * Math.PI * ((l / 2) % 2 === 0 ? -1 : 1) * ratio) / ((l + 2) * (l - 1));
    }
  }
  return a;
}
