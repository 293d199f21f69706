// Taubin's construction (paper Section 3): split every quad along a diagonal, then flip
// the diagonals of the quads on a spanning tree of the loops' adjacency, so that the
// triangles form exactly one closed strip per connected component.
#pragma once

#include "meander/quadrangulate.h"
#include "meander/spanning_tree.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace meander {

struct CycleOptions {
  TreeStrategy tree = TreeStrategy::random;
  uint64_t seed = 1;
};

// The Hamiltonian cycles of the triangulated quad mesh. Cycle k is the triangles
// triangles[cycle_start[k] .. cycle_start[k+1]) in order; consecutive triangles (and the
// last and the first) share a quad side. Each triangle is (p, apex, n): the apex is the
// corner between its two quad sides (the paper's p00 = p01), p and n the ends of its
// diagonal, in the quad's orientation. diagonal[q] is 0 when quad q is split along
// corners 0-2 and 1 along corners 1-3.
struct TriangleCycle {
  std::vector<std::array<int32_t, 3>> triangles;
  std::vector<int32_t> cycle_start{0};
  std::vector<uint8_t> diagonal;

  int32_t num_cycles() const { return int32_t(cycle_start.size()) - 1; }
};

// Builds one cycle per connected component of the quad mesh (components joined across
// quad sides). Every full quad contributes two triangles, a half quad one. Time O(quads)
// plus the spanning forest. Throws TopologyError if a full quad has a side with no
// neighbour (a quad mesh with boundary: only half quads may end at a boundary).
TriangleCycle hamiltonian_cycle(const QuadMesh& quads, const CycleOptions& options = {});

// Independent check of a cycle against its quad mesh, sharing no code with the
// construction: every triangle of the triangulation given by `diagonal` appears exactly
// once, consecutive triangles share two vertices, and there is exactly one cycle per
// connected component. Returns "" when it holds, else the first violation found.
std::string verify_cycle(const QuadMesh& quads, const TriangleCycle& cycle);

} // namespace meander
