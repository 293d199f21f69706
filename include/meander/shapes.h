// Meshes made by code: the bundled demo model, test fixtures and benchmark inputs, so
// that nothing third-party has to ship with the project.
#pragma once

#include "meander/mesh.h"

#include <cstdint>
#include <string_view>

namespace meander {

// Unit sphere as a latitude-longitude triangle mesh with about `faces` triangles
// (at least 8). Closed, genus 0.
PolygonMesh sphere(int64_t faces);

// Torus (major radius 1, minor 0.35) as a triangulated grid with about `faces`
// triangles (at least 18). Closed, genus 1.
PolygonMesh torus(int64_t faces);

// A smooth closed surface of the given genus (a row of `genus` holes in a rounded slab:
// genus 2 is the "pretzel"), as triangles: the voxel slab's Catmull-Clark limit surface
// (OpenSubdiv) at the level whose triangle count is nearest `faces`, each quad split along
// its shorter diagonal. genus >= 0.
PolygonMesh genus_surface(int genus, int64_t faces);

// The unit square in the z = 0 plane as an n x n grid of quads each split into two
// triangles (about `faces` triangles). An open disk: one boundary loop.
PolygonMesh grid(int64_t faces);

// A Möbius band of quads (about `faces` of them, at least 3 around and 1 across).
// Non-orientable, one boundary loop.
PolygonMesh moebius(int64_t faces);

// The named shape: "sphere", "torus", "pretzel" (genus 2), "genus" (uses `genus`),
// "grid", "moebius". Throws UsageError for another name or faces < 1.
PolygonMesh make_shape(std::string_view name, int64_t faces, int genus = 2);

// The same surface with its vertices and faces in a random order (each face keeps its
// corners), as some tools write meshes: the input for benchmarks and tests of scattered
// meshes (locality.h). The same seed gives the same order on every platform.
PolygonMesh shuffled(const PolygonMesh& mesh, uint64_t seed);

} // namespace meander
