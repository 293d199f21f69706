// The bodies of the fuzz targets, shared by the libFuzzer entry points (fuzz/*_fuzz.cpp)
// and by the regression test that replays every input the fuzzers ever crashed on
// (tests/regressions_test.cpp). Each takes arbitrary bytes, lets Meander's own errors
// (meander::Error) pass as a correct refusal, and returns "" when the result holds the
// stated invariants, else the first violation. Anything else (a crash, another
// exception, a sanitizer report, a hang) is a finding too, caught by the caller.
#pragma once

#include "meander/io.h"

#include <cstdint>
#include <span>
#include <string>

namespace meander::fuzz {

// read_mesh(bytes, format); a mesh it returns must be what io.h promises: at least one
// face, faces of >= 3 vertices, indices in range, finite positions. inspect() and
// repair() must then take it without failing otherwise than by a refusal.
std::string read_mesh_target(std::span<const uint8_t> bytes, MeshFormat format);

// A small mesh whose positions and indices are the bytes themselves (NaN, negative and
// out-of-range indices, repeated vertices, any face size): inspect() never throws, and
// what repair() returns passes inspect() clean and needs no second repair.
std::string repair_target(std::span<const uint8_t> bytes);

// A small mesh of arbitrary faces on grid points, repaired, then the whole curve
// pipeline under the quadrangulation, tree and seed the bytes pick: every triangle of the
// cycle once, consecutive triangles sharing an edge (also last to first), one cycle per
// component, one finite closed curve per cycle.
std::string curve_target(std::span<const uint8_t> bytes);

// A small mesh as curve_target makes it, then a wire of the kind, shape and options the
// bytes pick (constant: radius given or automatic; variable: s, t, thickness, levels):
// indices in range, finite positions, and exactly the triangles constant_wire_triangles
// or variable_wire_triangles announce; an empty constant wire only where no automatic
// radius exists.
std::string wire_target(std::span<const uint8_t> bytes);

// A small mesh as curve_target makes it, then its duotone under the quadrangulation,
// rule, tree, seed and tile style the bytes pick: every quad side joins the two colours,
// one separating loop and one finite curve per component, well-formed colour regions,
// and a textured surface that check_appearance accepts.
std::string duotone_target(std::span<const uint8_t> bytes);

// An OBJ with its MTL: the bytes before the first NUL are the OBJ (its `mtllib m.mtl`
// names the rest), those after it the MTL, beside a 2x1 PNG `t.png` that map_Kd may
// name. read_textured_mesh refuses them with Meander's error or returns a mesh as io.h
// promises with an appearance that check_appearance accepts.
std::string textured_obj_target(std::span<const uint8_t> bytes);

// read_texture on the bytes (JPEG through libjpeg-turbo; PNG, BMP, TGA, GIF, ... through stb_image):
// refused, or an image of at least one pixel with 4 bytes per pixel.
std::string image_target(std::span<const uint8_t> bytes);

// The body of the studio's POST /api/make (parse_make_request): refused with a
// UsageError, or parameters within the CLI's ranges.
std::string make_request_target(std::span<const uint8_t> bytes);

// An upload to the studio (load_studio_surface): the bytes up to the first newline are
// the file name as the browser sent it (any path, any extension), the rest the file.
// Refused with Meander's own error, or a repaired mesh as repair() promises.
std::string upload_target(std::span<const uint8_t> bytes);

// The bytes as one connection to the studio's HTTP server (StudioServer::serve_bytes: its
// own connection code and httplib's parsing, without a socket), after an upload that
// made a session: every "SESSION-ID-OF-THE-FUZZ-TARGET-00" in the bytes is that session's
// id, so that make and result requests reach real work. The server must answer only
// with well-framed HTTP answers (status line, headers, Content-Length bytes of body),
// none of them a 5xx, at most one per request the connection may carry.
std::string http_target(std::span<const uint8_t> bytes);

} // namespace meander::fuzz
