#pragma once
/// Process-wide allocator settings for canopy's programs. Resolution and detection allocate and
/// free many large working arrays per round (search state, candidate lists, contact buffers);
/// glibc's defaults hand every block above 128 KiB-32 MiB (its adaptive mmap threshold) back to
/// the kernel when freed and trim the heap top above 128 KiB, so the next round's arrays are
/// faulted in and zeroed page by page again (about 10% of a 1,000-plant resolution went to page
/// faults). Keeping freed memory in the process trades a higher resident peak (at most the
/// largest round's working set, which the process reached anyway) for none of that.
#include <malloc.h>

namespace canopy {

inline void keep_freed_memory() {
#ifdef M_MMAP_THRESHOLD
  mallopt(M_MMAP_THRESHOLD, 32 << 20);   // glibc's largest: blocks up to 32 MiB come from the heap
  mallopt(M_TRIM_THRESHOLD, 256 << 20);  // the heap top is trimmed only above 256 MiB free
  mallopt(M_TOP_PAD, 256 << 20);         // and grows 256 MiB beyond what it needs each time
#endif
}

}  // namespace canopy
