// An independent reader and checker of the files `meander curve` writes: the cycle
// certificate (--triangles, OBJ with one `o` group per cycle) and the curve (OBJ with
// closed `l` elements). It shares no code with the library on purpose.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace meander::test {

struct ObjGroups {
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::vector<std::array<int, 3>>> groups; // triangles (0-based) per `o` group
  std::vector<std::vector<int>> lines;                 // `l` elements (0-based)
};

ObjGroups parse_obj_groups(const std::filesystem::path& path);

struct CertificateFacts {
  std::string problem; // "" when the certificate holds
  int cycles = 0;
  long triangles = 0;
  long euler_characteristic = 0; // of the certificate's triangle mesh
  int boundary_edges = 0;
};

// The certificate holds when: triangles are distinct, consecutive triangles of each
// group (and last to first) share an edge, no edge has more than two triangles, and no
// two groups share an edge (a shared edge between two cycles is a missed merge).
CertificateFacts check_certificate(const ObjGroups& certificate);

// Largest distance from a curve point to the certificate triangles that carry it,
// divided by their longest edge. Curve k must have K points per triangle of cycle k
// (K = samples per segment; the closing point repeats the first): sample j lies on the
// spline segment built from the control points of triangles j/K - 1 .. j/K + 2.
double curve_distance_ratio(const ObjGroups& curve, const ObjGroups& certificate);

} // namespace meander::test
