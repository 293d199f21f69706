// The studio's view bytes (studio_view_bytes) decoded as the page decodes them, with
// meshoptimizer's decoders: for the tests that check what the page draws.
#pragma once

#include <meshoptimizer.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace meander::test {

struct DecodedView {
  uint32_t vertices = 0, triangles = 0, segments = 0, flags = 0;
  float box[6] = {};
  std::vector<float> positions;     // 3 per vertex, from their 16-bit steps of the box's largest side
  std::vector<int8_t> normals;      // 4 per vertex (x, y, z, 0), with flag 2
  std::vector<float> texcoords;     // 2 per vertex, from their 16-bit fractions, with flag 1
  std::vector<uint32_t> triangle_indices, segment_indices;
  bool ok = false; // every array decoded and the bytes used up
};

inline DecodedView decode_view(const std::string& bytes) {
  DecodedView view;
  if (bytes.size() < 48 || bytes.substr(0, 4) != "MND3") {
    ADD_FAILURE() << "not a view: " << bytes.substr(0, 4);
    return view;
  }
  std::memcpy(&view.vertices, bytes.data() + 4, 4);
  std::memcpy(&view.triangles, bytes.data() + 8, 4);
  std::memcpy(&view.segments, bytes.data() + 12, 4);
  std::memcpy(&view.flags, bytes.data() + 16, 4);
  std::memcpy(view.box, bytes.data() + 24, sizeof view.box);
  size_t at = 48;
  // The next array's bytes (its count, then the bytes padded to 4), or false.
  auto next = [&](auto&& decode) {
    uint32_t length = 0;
    if (at + 4 > bytes.size()) return false;
    std::memcpy(&length, bytes.data() + at, 4);
    if (at + 4 + length > bytes.size()) return false;
    const bool decoded = decode(reinterpret_cast<const unsigned char*>(bytes.data() + at + 4), size_t(length)) == 0;
    at += 4 + (length + 3) / 4 * 4;
    return decoded;
  };
  const size_t v = view.vertices;
  auto vertices = [&](auto& out, size_t per_vertex) {
    out.resize(v * per_vertex);
    return next([&](const unsigned char* data, size_t size) {
      return meshopt_decodeVertexBuffer(out.data(), v, per_vertex * sizeof(out[0]), data, size);
    });
  };
  std::vector<uint16_t> steps;
  bool ok = vertices(steps, 4);
  const float side = std::max({view.box[3] - view.box[0], view.box[4] - view.box[1], view.box[5] - view.box[2], 1e-30f});
  view.positions.resize(3 * v);
  for (size_t i = 0; ok && i < 3 * v; ++i) view.positions[i] = view.box[i % 3] + float(steps[i + i / 3]) / 65535 * side;
  if (ok && (view.flags & 2)) ok = vertices(view.normals, 4);
  if (ok && (view.flags & 1)) {
    std::vector<uint16_t> fractions;
    ok = vertices(fractions, 2);
    view.texcoords.assign(fractions.begin(), fractions.end());
    for (float& t : view.texcoords) t /= 65535;
  }
  if (ok && view.triangles > 0) {
    view.triangle_indices.resize(3 * size_t(view.triangles));
    ok = next([&](const unsigned char* data, size_t size) {
      return meshopt_decodeIndexBuffer(view.triangle_indices.data(), view.triangle_indices.size(), 4, data, size);
    });
  }
  if (ok && view.segments > 0) {
    view.segment_indices.resize(2 * size_t(view.segments));
    ok = next([&](const unsigned char* data, size_t size) {
      return meshopt_decodeIndexSequence(view.segment_indices.data(), view.segment_indices.size(), 4, data, size);
    });
  }
  view.ok = ok && at == bytes.size();
  EXPECT_TRUE(view.ok) << "the view's arrays do not decode to its counts, or bytes are left over";
  return view;
}

} // namespace meander::test
