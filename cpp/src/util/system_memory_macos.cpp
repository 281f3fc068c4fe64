// system_memory.h on macOS (arm64 and x86_64):
//   available: free plus inactive pages from host_statistics64 (free_count includes the speculative
//     pages; inactive pages are what the kernel reclaims first: the analogue of MemAvailable);
//   total: sysctl hw.memsize;
//   release: malloc_zone_pressure_relief on every malloc zone (what the system itself calls under
//     memory pressure).
#include "gauss/util/system_memory.h"

#include <mach/mach.h>
#include <malloc/malloc.h>
#include <sys/sysctl.h>
#include <sys/types.h>

#include <algorithm>

namespace gauss {

int64_t system_available_memory_bytes() {
  const mach_port_t host = mach_host_self();
  vm_size_t page_size = 0;
  vm_statistics64_data_t stats{};
  mach_msg_type_number_t count = HOST_VM_INFO64_COUNT;
  const bool ok = host_page_size(host, &page_size) == KERN_SUCCESS &&
                  host_statistics64(host, HOST_VM_INFO64, reinterpret_cast<host_info64_t>(&stats), &count) ==
                      KERN_SUCCESS;
  mach_port_deallocate(mach_task_self(), host);  // mach_host_self() added a reference
  if (!ok || page_size == 0) return kUnknownMemory;
  const int64_t pages = static_cast<int64_t>(stats.free_count) + static_cast<int64_t>(stats.inactive_count);
  return std::min(pages * static_cast<int64_t>(page_size), system_total_memory_bytes());
}

int64_t system_total_memory_bytes() {
  uint64_t bytes = 0;
  size_t size = sizeof bytes;
  if (sysctlbyname("hw.memsize", &bytes, &size, nullptr, 0) != 0 || size != sizeof bytes || bytes == 0)
    return kUnknownMemory;
  return bytes >= static_cast<uint64_t>(kUnknownMemory) ? kUnknownMemory : static_cast<int64_t>(bytes);
}

void release_free_memory() { malloc_zone_pressure_relief(nullptr, 0); }

}  // namespace gauss
