// Parallel loops over a fixed number of chunks, for passes whose results must come out in
// the same order whatever the number of threads. Internal to the library.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include <tbb/parallel_for.h>

namespace meander {

constexpr int32_t kChunks = 64;

// Where chunk c of items [0, count) begins (count for c = kChunks and for chunks past
// the end).
inline int32_t chunk_begin(int32_t count, int32_t c) { return std::min(count, c * ((count + kChunks - 1) / kChunks)); }

// Runs body(chunk, begin, end) over items [0, count) cut into kChunks ranges, in
// parallel; ranges past the end are empty.
template <typename Body>
void for_chunks(int32_t count, Body&& body) {
  tbb::parallel_for(0, kChunks, [&](int32_t c) { body(c, chunk_begin(count, c), chunk_begin(count, c + 1)); });
}

// Where each chunk's output starts, when counted(begin, end) is the number of outputs of
// the items [begin, end) of a chunk: the outputs of all chunks laid end to end in chunk
// order, their total last.
template <typename Count>
std::array<int32_t, kChunks + 1> chunk_offsets(int32_t count, Count&& counted) {
  std::array<int32_t, kChunks + 1> at{};
  for_chunks(count, [&](int32_t c, int32_t begin, int32_t end) { at[size_t(c) + 1] = counted(begin, end); });
  for (int32_t c = 0; c < kChunks; ++c) at[size_t(c) + 1] += at[size_t(c)];
  return at;
}

} // namespace meander
