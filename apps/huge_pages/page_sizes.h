// Whether large blocks go on huge pages, chosen by what fresh pages of each size have
// cost the process so far, since which is cheaper depends on the host, not on Meander.
//
// On an AMD EPYC host, small pages made the 10M-triangle curve 1.8 s slower (5.04-5.19 s
// against 3.11-3.48 s; user time 5.6-5.8 against 3.1-3.3 s), presumably what that host
// charged at each page's first use, which the measurement here includes (prefault in
// huge_pages.cpp touches every page). On an Intel Xeon host of the same kind of
// virtual machine, small pages cost nothing in user time, while a fresh huge page took 7
// times as long to fault in as its 512 small ones (2.4 against 0.33 ms/MiB: the host backs
// anew the large free blocks that the guest reported to it, and small pages come from
// fragments it still backs), and the run took 2.30-2.38 s against 3.06-3.16 s
// (docs/benchmarks.md). So the first large block has its first few huge pages tried and
// the rest put on small ones, and from then on every block takes the size that cost less
// per byte of late. The size chosen keeps being measured, so that a choice a lucky start
// made is taken back. The size not chosen is not tried again: in a process that keeps
// allocating (the benchmarks' loops) huge pages tried among small ones cost 0.1-1.6
// ms/MiB, mostly more than small ones (0.12-0.15), though the same loop on huge pages
// alone took them back from its own freed ones at little cost (read + connectivity of
// the 10M sphere: 356 ms all on huge pages, 429 ms as chosen here).
#pragma once

#include <algorithm>
#include <cstdint>
#include <mutex>

namespace meander {

class PageSizes {
public:
  enum Size { small, huge };
  static constexpr uintptr_t kHugePage = uintptr_t(2) << 20;
  // Enough huge pages that one still backed by chance does not decide. A measurement of
  // this many bytes or more replaces what was known of its size's cost (what pages cost
  // changes within seconds); a smaller one weighs in proportion.
  static constexpr uintptr_t kSample = 4 * kHugePage;

  // Where the page-aligned [begin, end) changes from huge pages (before) to small ones.
  uintptr_t split(uintptr_t begin, uintptr_t end) {
    std::lock_guard lock(mutex_);
    if (bytes_[huge] < kSample) return std::min(end, ((begin + kHugePage - 1) & ~(kHugePage - 1)) + kSample);
    if (bytes_[small] < kSample) return begin;
    return cost_[huge] <= cost_[small] ? end : begin;
  }

  // What taking `bytes` of fresh pages of `size` cost, in seconds.
  void record(Size size, uintptr_t bytes, double seconds) {
    if (bytes == 0) return;
    std::lock_guard lock(mutex_);
    const double weight = bytes_[size] == 0 ? 1.0 : std::min(1.0, double(bytes) / double(kSample));
    cost_[size] += weight * (seconds / double(bytes) - cost_[size]);
    bytes_[size] += bytes;
  }

private:
  std::mutex mutex_;
  uintptr_t bytes_[2] = {0, 0}; // measured in all
  double cost_[2] = {0, 0};     // seconds per byte, of late
};

} // namespace meander
