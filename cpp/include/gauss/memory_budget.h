#pragma once
// How much memory a set-up may still allocate, so that a mesh too big for the machine is refused
// with a clear error before the allocation instead of the kernel's OOM killer ending the process
// (in Blender: the artist's unsaved session).
#include <cstdint>
#include <stdexcept>
#include <string>

namespace gauss {

// Thrown when a set-up would need more memory than available_memory_bytes() (MemoryError in Python).
class OutOfMemory : public std::runtime_error {
 public:
  explicit OutOfMemory(const std::string& what) : std::runtime_error(what) {}
};

// Bytes this process can still allocate without being killed or refused: the smallest of
//   - MemAvailable in /proc/meminfo (free memory plus what the kernel can reclaim),
//   - the address-space limit (RLIMIT_AS) minus the current virtual size,
//   - every enclosing cgroup's memory limit minus its usage (v2 memory.max, v1 memory.limit_in_bytes;
//     reclaimable file cache not counted as usage).
// Sources that do not exist or cannot be read are skipped; if none can be read the result is
// INT64_MAX (no known limit).
//
// GAUSS_MEMORY_BUDGET_MB, if set in the environment to a number, replaces all of the above (in
// mebibytes). Nothing else reads it; it lets tests exercise the too-big path without filling memory.
int64_t available_memory_bytes();

// Throws OutOfMemory, saying what `what` needed (e.g. "the factorization of 501,128 unknowns"), if
// `needed` bytes exceed available_memory_bytes().
void check_memory(int64_t needed, const std::string& what);

// Hands the pages of freed heap memory back to the system. glibc keeps much of what a set-up's
// temporaries freed resident: blocks freed between live ones in its heap, and the arenas of the pool
// threads that ordered and factored the mesh (on the 501K mesh of scripts/measure_scale.sh, 115 MB
// after the ordering alone). The factorization calls it before it allocates the factor and again at
// its end, so that neither the factor nor the steps sit on top of that memory, and the memory check
// sees it as available. A few milliseconds; a no-op where the C library is not glibc.
void release_free_memory();

// "1.23 GB" / "456 MB": sizes in error messages.
std::string format_bytes(int64_t bytes);

}  // namespace gauss
