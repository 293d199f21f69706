// Writing the cycle's curves to a file without holding them in memory (the I/O layer
// above curve.h): what `meander curve` does on large meshes.
#pragma once

#include "meander/curve.h"
#include "meander/hamiltonian.h"
#include "meander/io.h"

#include <cstdint>
#include <filesystem>
#include <memory>

namespace meander {

// write_polylines(cycle_curves(quads, cycle, options), path), byte for byte, without the
// curves in memory: each block of points is sampled as the writer reaches it (on all
// cores for PLY), so only a few blocks exist at once instead of 12 bytes a point for the
// whole curve (docs/curve.md, "Large meshes"). Returns the number of points
// written. Throws what cycle_curves and write_polylines throw, a bad samples before the
// file is made.
int64_t write_cycle_curves(const QuadMesh& quads, const TriangleCycle& cycle, const CurveOptions& options,
                           const std::filesystem::path& path);

// write_cycle_curves in two steps, so that the file is written while the cycles are
// made: made from the quad mesh alone, the writer counts the points and, for PLY, writes
// on a thread of its own the header and the edges as if the points made one closed curve
// (a GB for a 10M-triangle mesh, beside the cycle's serial spanning tree), then the
// points of the triangles that observer(), passed to hamiltonian_cycle, is shown walked
// (beside the serial walk). finish() writes the points left, turns the last edge of
// each curve back to its own first point when there are several, and commits. `quads`
// must stay alive and unchanged until then; destroyed without finish(), the writer
// leaves no file. The constructor throws a bad samples and a file that cannot be made;
// finish() what the thread met, and what write_cycle_curves throws.
class CycleCurveWriter {
public:
  CycleCurveWriter(const QuadMesh& quads, const CurveOptions& options, const std::filesystem::path& path);
  ~CycleCurveWriter();
  CycleCurveWriter(const CycleCurveWriter&) = delete;
  CycleCurveWriter& operator=(const CycleCurveWriter&) = delete;

  // For hamiltonian_cycle; null when the writer has no use for it (not a PLY).
  const WalkObserver* observer() const;

  // `cycle` must be hamiltonian_cycle(quads, ...). Returns the number of points written.
  int64_t finish(const TriangleCycle& cycle);

  // How many points the thread wrote before finish() (a figure for tests and benchmarks).
  int64_t points_written_while_walking() const;

private:
  struct File;
  std::unique_ptr<File> file_;
};

} // namespace meander
