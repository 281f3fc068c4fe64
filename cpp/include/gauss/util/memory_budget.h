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

// Bytes this process can still allocate without being killed or refused: what the system reports
// (system_available_memory_bytes() in system_memory.h, per platform), INT64_MAX if it reports nothing.
//
// GAUSS_MEMORY_BUDGET_MB, if set in the environment to a number, replaces the system's figure (in
// mebibytes). Nothing else reads it; it lets tests exercise the too-big path without filling memory.
int64_t available_memory_bytes();

// Throws OutOfMemory, saying what `what` needed (e.g. "the factorization of 501,128 unknowns"), if
// `needed` bytes exceed available_memory_bytes().
void check_memory(int64_t needed, const std::string& what);

// "1.23 GB" / "456 MB": sizes in error messages.
std::string format_bytes(int64_t bytes);

}  // namespace gauss
