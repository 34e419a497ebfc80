// emitter_solve.cpp — see radiosity/emitter_solve.h.
#include "radiosity/emitter_solve.h"

#include <stdexcept>

#include "radiosity/materials.h"

namespace prt::radiosity {

std::vector<EmitterGroup> emitter_groups(const scene::Scene& scene) {
  std::vector<EmitterGroup> groups;
  std::vector<std::string> first_primitive;
  for (const scene::ScenePrimitive& p : scene.primitives) {
    if (p.triangle_count == 0 || p.emission == glm::vec3(0.f)) continue;
    const std::string name = p.material.empty() ? "<none>" : p.material;
    std::size_t g = 0;
    while (g < groups.size() && groups[g].name != name) ++g;
    if (g == groups.size()) {
      groups.push_back({name, p.emission, {}});
      first_primitive.push_back(p.name);
    } else if (groups[g].emission != p.emission) {
      throw std::invalid_argument(scene.source_path + ": emitter " + name + ": primitives " +
                                  first_primitive[g] + " and " + p.name + " emit differently " +
                                  describe_colour(groups[g].emission) + " vs " +
                                  describe_colour(p.emission));
    }
    for (uint32_t k = 0; k < p.triangle_count; ++k)
      if (p.first_triangle + k < scene.triangles.size())
        groups[g].triangles.push_back(p.first_triangle + k);
  }
  return groups;
}

prt::EmitterResponses emitter_responses(
    const scene::Scene& scene, const std::vector<Patch>& patches,
    const std::function<Solution(const std::vector<Patch>& lit)>& solve,
    std::vector<EmitterSolveReport>* reports) {
  const std::vector<EmitterGroup> groups = emitter_groups(scene);
  if (groups.empty()) throw std::invalid_argument(scene.source_path + ": nothing emits light");
  prt::EmitterResponses out;
  const std::size_t v_count = scene.vertex_count();
  out.positions.reserve(3 * v_count);
  out.normals.reserve(3 * v_count);
  for (std::size_t v = 0; v < v_count; ++v)
    for (int c = 0; c < 3; ++c) {
      out.positions.push_back(scene.positions[v][c]);
      out.normals.push_back(scene.normals[v][c]);
    }
  for (const glm::uvec3& t : scene.triangles)
    for (int c = 0; c < 3; ++c) out.triangles.push_back(t[c]);
  out.responses.reserve(3 * v_count * groups.size());
  std::vector<Patch> lit = patches;
  for (const EmitterGroup& group : groups) {
    for (Patch& p : lit) p.emission = glm::dvec3(0.0);
    for (uint32_t t : group.triangles) lit[t].emission = glm::dvec3(1.0);
    const Solution solution = solve(lit);
    const std::vector<float> vertex = vertex_radiance(scene, lit, solution.radiance);
    out.responses.insert(out.responses.end(), vertex.begin(), vertex.end());
    out.emitters.push_back({group.name, {group.emission.x, group.emission.y, group.emission.z}});
    if (reports)
      reports->push_back(
          {group.name, solution.iterations, solution.converged, solution.relative_unshot});
  }
  return out;
}

prt::EmitterResponses solve_emitter_responses(const scene::Scene& scene,
                                              const std::vector<Patch>& patches,
                                              const FormFactorMatrix& f,
                                              const SolveOptions& options,
                                              std::vector<EmitterSolveReport>* reports) {
  if (options.solver == SolverKind::Progressive)
    throw std::invalid_argument(
        "per-emitter responses need a full-matrix solver (gauss-seidel or jacobi), not "
        "progressive");
  if (emitter_groups(scene).empty())
    throw std::invalid_argument(scene.source_path + ": nothing emits light");
  // K depends on the geometry only (not on emission or albedo): one for every emitter's solve.
  const GatherMatrix k = make_gather_matrix(patches, f);
  return emitter_responses(
      scene, patches, [&](const std::vector<Patch>& lit) { return solve_matrix(lit, k, options); },
      reports);
}

}  // namespace prt::radiosity
