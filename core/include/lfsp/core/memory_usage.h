#pragma once

namespace lfsp {

// The process's resident memory now (/proc/self/statm) and its peak so far (getrusage's ru_maxrss), in MB of 2^20
// bytes (as `lfsp_bench` prints peaks); 0 where the system does not tell. Steps record both beside their seconds,
// so a summary shows where the memory goes as well as the time (issue 46).
double ResidentMegabytes();
double PeakResidentMegabytes();

}  // namespace lfsp
