#pragma once
// What the operating system says about memory: the one place that differs per platform. Each
// platform has its own implementation file (CMakeLists.txt picks one):
//   cpp/src/util/system_memory_linux.cpp    Linux: /proc/meminfo, cgroups v1/v2, RLIMIT_AS; glibc's malloc_trim
//   cpp/src/util/system_memory_windows.cpp  Windows: GlobalMemoryStatusEx; the C runtime's _heapmin
//   cpp/src/util/system_memory_macos.cpp    macOS: sysctl hw.memsize, host_statistics64; malloc_zone_pressure_relief
// memory_budget.h builds the solver's memory check on top of this.
#include <cstdint>
#include <limits>

namespace gauss {

// What the queries return when the system does not say.
inline constexpr int64_t kUnknownMemory = std::numeric_limits<int64_t>::max();

// Bytes of physical memory this process can still allocate and use without being killed, refused or
// swapped out, as the system reports it now (see each implementation for its sources); at most
// system_total_memory_bytes(). kUnknownMemory if no source can be read.
int64_t system_available_memory_bytes();

// Bytes of physical memory the machine has (kUnknownMemory if the system does not say).
int64_t system_total_memory_bytes();

// Hands the pages of freed heap memory back to the system. glibc keeps much of what a set-up's
// temporaries freed resident: blocks freed between live ones in its heap, and the arenas of the pool
// threads that ordered and factored the mesh. The factorization calls it before it allocates the
// factor and again at its end, so that neither the factor nor the steps sit on top of that memory,
// and the memory check sees it as available (its cost and gain: docs/performance.md#set-up-at-scale).
// On C libraries that return freed pages by themselves (musl) it does nothing.
void release_free_memory();

}  // namespace gauss
