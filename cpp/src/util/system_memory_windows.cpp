// system_memory.h on Windows (MSVC and MinGW-w64):
//   available: GlobalMemoryStatusEx's smallest of
//     - ullAvailPhys: physical memory free or on the standby list (the analogue of MemAvailable),
//     - ullAvailPageFile: what this process may still commit; inside a job object with a memory limit
//       (Windows containers, some CI runners) it is the job's limit, the analogue of a cgroup's,
//     - ullAvailVirtual: the address space left (small only for 32-bit processes);
//   total: ullTotalPhys;
//   release: the C runtime's _heapmin (UCRT and msvcrt both decommit the free pages of their heap).
#include "gauss/util/system_memory.h"

#ifndef WIN32_LEAN_AND_MEAN
#define WIN32_LEAN_AND_MEAN
#endif
#ifndef NOMINMAX
#define NOMINMAX
#endif
#include <windows.h>
#include <malloc.h>

#include <algorithm>

namespace gauss {
namespace {

bool memory_status(MEMORYSTATUSEX& status) {
  status = MEMORYSTATUSEX{};
  status.dwLength = sizeof status;
  return GlobalMemoryStatusEx(&status) != 0;
}

int64_t to_bytes(DWORDLONG value) {
  return value >= static_cast<DWORDLONG>(kUnknownMemory) ? kUnknownMemory : static_cast<int64_t>(value);
}

}  // namespace

int64_t system_available_memory_bytes() {
  MEMORYSTATUSEX status;
  if (!memory_status(status)) return kUnknownMemory;
  return std::min({to_bytes(status.ullAvailPhys), to_bytes(status.ullAvailPageFile), to_bytes(status.ullAvailVirtual)});
}

int64_t system_total_memory_bytes() {
  MEMORYSTATUSEX status;
  return memory_status(status) ? to_bytes(status.ullTotalPhys) : kUnknownMemory;
}

void release_free_memory() { _heapmin(); }

}  // namespace gauss
