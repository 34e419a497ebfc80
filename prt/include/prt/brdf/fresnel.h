// prt/brdf/fresnel.h — Fresnel reflectance: the exact dielectric formula and Schlick's
// approximation.
//
// cos_i is the cosine between the incident direction and the (micro-)normal, in [0, 1].
// eta = n_t / n_i is the relative index of refraction across the interface (1.5 for glass in
// air; below 1 means leaving a denser medium, with total internal reflection past the critical
// angle). Light is unpolarised: F = (R_s + R_p) / 2 with the Fresnel equations [33].
// At normal incidence F = ((η − 1)/(η + 1))², which is also Schlick's F0 for the dielectric.
// Schlick [34]: F ≈ F0 + (1 − F0)(1 − cos_i)⁵. Compiles as C++17.
// References: [33], [34] of docs/REFERENCES.md.
#pragma once

namespace prt::brdf {

// Exact unpolarised dielectric reflectance; 1 under total internal reflection.
double fresnel_dielectric(double cos_i, double eta);
// ((η − 1)/(η + 1))², the reflectance at normal incidence.
double fresnel_f0(double eta);
// Schlick's approximation with reflectance f0 at normal incidence.
double fresnel_schlick(double cos_i, double f0);

}  // namespace prt::brdf
