#include "lccp/process.hpp"

#include <malloc.h>

namespace lccp {

void keep_freed_memory_for_next_frames() {
  constexpr int kOneGiB = 1 << 30;
  mallopt(M_MMAP_THRESHOLD, kOneGiB);
  mallopt(M_TRIM_THRESHOLD, kOneGiB);
}

}  // namespace lccp
