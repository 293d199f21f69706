#include "meander/default_init.h"

#ifdef __linux__
#include <sys/mman.h>
#endif

namespace meander {

void advise_huge_pages([[maybe_unused]] void* block, [[maybe_unused]] size_t bytes) noexcept {
#ifdef MADV_HUGEPAGE
  madvise(block, bytes, MADV_HUGEPAGE);
#endif
}

} // namespace meander
