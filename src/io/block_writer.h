// Binary formats whose records can be formatted independently (STL triangles, PLY
// faces) are formatted in blocks on all cores and written in order, so that a writer
// streams tens of millions of triangles per second (issue 4: >= 20 M/s).
#pragma once

#include "io/sink.h"

#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace meander::io {

// Writes items 0..count-1 in blocks of `block` items: format(begin, end, bytes) resizes
// `bytes` to the bytes of items [begin, end) and fills them (a buffer of an earlier
// block, so resizing to the same size costs nothing). Blocks are formatted in parallel
// and passed to out.bytes() in order, with a few blocks in flight per core, so memory
// stays bounded whatever the count. Exceptions from `format` or `out` propagate.
template <class Format> void write_blocks(Sink& out, int64_t count, int64_t block, Format&& format) {
  if (count <= 0) return;
  const size_t tokens = 2 * size_t(std::max(1, tbb::this_task_arena::max_concurrency()));
  // In-order output retires blocks in order, so the blocks in flight are always fewer
  // than `tokens` consecutive ones and block k can use buffer k % tokens.
  std::vector<std::vector<char>> buffers(tokens);
  struct Block {
    int64_t begin = 0, end = 0;
    std::vector<char>* bytes = nullptr;
  };
  int64_t next = 0;
  size_t index = 0;
  tbb::parallel_pipeline(
      tokens,
      tbb::make_filter<void, Block>(tbb::filter_mode::serial_in_order,
                                    [&](tbb::flow_control& control) -> Block {
                                      if (next >= count) {
                                        control.stop();
                                        return {};
                                      }
                                      const Block b{next, std::min(count, next + block), &buffers[index++ % tokens]};
                                      next = b.end;
                                      return b;
                                    }) &
          tbb::make_filter<Block, Block>(tbb::filter_mode::parallel,
                                         [&](Block b) {
                                           format(b.begin, b.end, *b.bytes);
                                           return b;
                                         }) &
          tbb::make_filter<Block, void>(tbb::filter_mode::serial_in_order,
                                        [&](Block b) { out.bytes(b.bytes->data(), b.bytes->size()); }));
}

} // namespace meander::io
