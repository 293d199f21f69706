// One closed curve over a torus made in code, with Meander's core alone: no files, no
// sculpture. Prints the cycle's size and the curve's points; exits 1 if the independent
// check refuses the cycle.
#include "meander/connectivity.h"
#include "meander/curve.h"
#include "meander/hamiltonian.h"
#include "meander/quadrangulate.h"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

int main() {
  // A torus of 24 x 12 quads: radii 1 and 0.3.
  constexpr int around = 24, across = 12;
  meander::PolygonMesh torus;
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < across; ++j) {
      const float u = 2 * std::numbers::pi_v<float> * float(i) / around;
      const float v = 2 * std::numbers::pi_v<float> * float(j) / across;
      const float r = 1 + 0.3f * std::cos(v);
      torus.positions.push_back({r * std::cos(u), r * std::sin(u), 0.3f * std::sin(v)});
    }
  const auto vertex = [](int i, int j) { return int32_t((i % around) * across + j % across); };
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < across; ++j)
      torus.add_face({vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1), vertex(i, j + 1)});

  // The paper's pipeline: quads (here the dual-simplest, which takes any polygon mesh),
  // the Hamiltonian cycle of their triangles, and the smooth curve through it.
  const meander::QuadMesh quads = meander::dual_simplest(torus, meander::build_connectivity(torus));
  const meander::TriangleCycle cycle = meander::hamiltonian_cycle(quads, {.seed = 7});
  if (const std::string problem = meander::verify_cycle(quads, cycle); !problem.empty()) {
    std::fprintf(stderr, "torus_curve: the cycle is not Hamiltonian: %s\n", problem.c_str());
    return 1;
  }
  const meander::Polylines curve = meander::cycle_curves(quads, cycle, {.samples = 4});
  std::printf("%d quads, %d cycle(s) through %d triangles, a curve of %zu points\n", quads.num_quads(),
              cycle.num_cycles(), cycle.num_triangles(), curve.points.size());
  return cycle.num_cycles() == 1 && curve.points.size() == size_t(4 * cycle.num_triangles()) ? 0 : 1;
}
