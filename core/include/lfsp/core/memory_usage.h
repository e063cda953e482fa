#pragma once

namespace lfsp {

// The process's resident memory now (/proc/self/statm) and its peak so far (getrusage's ru_maxrss), in MB of 2^20
// bytes (as `lfsp_bench` prints peaks); 0 where the system does not tell. Steps record both beside their seconds,
// so a summary shows where the memory goes as well as the time (issue 46).
double ResidentMegabytes();
double PeakResidentMegabytes();

// Gives the pages of freed heap blocks back to the system (glibc's malloc_trim; nothing elsewhere). The `lfsp`
// executable keeps freed blocks in its heap so a stage reuses them without page faults (apps/lfsp_main.cc), but
// blocks a step has freed and that nothing later fits into would then count in the peak: a step that has just
// freed sensor-size buffers calls this before the next large allocation (issue 46; docs/DESIGN.md, "Peak memory").
void ReturnFreedMemory();

// Gives back to the system the pages that lie wholly within [begin, end) of a live allocation whose contents the
// caller will not read again: they read as zero afterwards, and the allocation is still freed as usual. A step that
// consumes a large input front to back calls this behind itself, so its output fills up as the input empties
// (madvise MADV_DONTNEED on Linux; nothing elsewhere).
void DiscardPages(void* begin, void* end);

}  // namespace lfsp
