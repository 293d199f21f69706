// One reader of read_mesh, chosen at build time by MEANDER_FUZZ_FORMAT (obj, ply, stl,
// off, gltf): fuzz/CMakeLists.txt builds this file once per format.
#include "fuzz_main.h"
#include "fuzz_targets.h"

MEANDER_FUZZ_ENTRY(meander::fuzz::read_mesh_target(bytes, meander::MeshFormat::MEANDER_FUZZ_FORMAT))
