// radiosity/emitter_solve.h — one radiosity solution per emitter, for relighting the emitters
// afterwards (prt/emitters/emitter_responses.h: L = Σ_e c_e ⊙ R_e, exact because the radiosity
// equation is linear in the emission E, channel by channel).
//
// An emitter is an emitting material: every primitive with a non-zero emission is grouped by
// its material name (primitives without a material name form the emitter "<none>"); all
// primitives of one emitter must have the same emission. For each emitter, in order of first
// appearance among the primitives, the equation of radiosity/solver.h is solved with that
// emitter's patches at unit white emission (1, 1, 1) and every other patch dark, on the same
// form-factor matrix (computed once by the caller), with the same albedos (emitters keep
// reflecting with their own). The per-vertex response is the area-weighted vertex radiance of
// radiosity/patches.h, exit radiance per unit emitted radiance. Each solve stops at the
// tolerance of `options` relative to that emitter's own emitted power.
// Frame and units: the Scene's.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/emitters/emitter_responses.h"
#include "radiosity/form_factors.h"
#include "radiosity/patches.h"
#include "radiosity/solver.h"
#include "scene/scene.h"

namespace prt::radiosity {

struct EmitterGroup {
  std::string name;                 // the material's name, or "<none>"
  glm::vec3 emission{0.f};          // its emission (exit radiance, linear RGB)
  std::vector<uint32_t> triangles;  // the patches (scene triangles) that emit
};

// The emitters of `scene`. Throws std::invalid_argument "PATH: emitter M: primitives A and B
// emit differently (…)" when one material's primitives differ in emission.
std::vector<EmitterGroup> emitter_groups(const scene::Scene& scene);

struct EmitterSolveReport {
  std::string name;
  std::size_t iterations = 0;
  bool converged = false;
  double relative_unshot = 0;
};

// One response per emitter of `scene` (whose triangles are `patches`, make_patches): each
// emitter's triangles emit unit white, every other patch nothing, and `solve` returns the
// patches' radiance under that emission; the responses are its vertex radiance. The loop shared
// by the dense and the hierarchical solvers. `reports` (optional) receives one entry per
// emitter. Throws std::invalid_argument when nothing emits.
prt::EmitterResponses emitter_responses(
    const scene::Scene& scene, const std::vector<Patch>& patches,
    const std::function<Solution(const std::vector<Patch>& lit)>& solve,
    std::vector<EmitterSolveReport>* reports = nullptr);

// The responses of every emitter of `scene` (whose triangles are `patches`, make_patches) under
// the form factors `f`, solved with options.solver (GaussSeidel or Jacobi). `reports`
// (optional) receives one entry per emitter. Throws std::invalid_argument when nothing emits or
// the solver is Progressive.
prt::EmitterResponses solve_emitter_responses(const scene::Scene& scene,
                                              const std::vector<Patch>& patches,
                                              const FormFactorMatrix& f,
                                              const SolveOptions& options,
                                              std::vector<EmitterSolveReport>* reports = nullptr);

}  // namespace prt::radiosity
