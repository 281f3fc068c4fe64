#include "gauss/util/memory_budget.h"

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

#include "gauss/util/system_memory.h"

namespace gauss {

int64_t available_memory_bytes() {
  if (const char* budget = std::getenv("GAUSS_MEMORY_BUDGET_MB")) {
    char* end = nullptr;
    const double mb = std::strtod(budget, &end);
    if (end != budget && mb >= 0 && mb < 1e12) return static_cast<int64_t>(mb * 1024 * 1024);
  }
  return system_available_memory_bytes();
}

std::string format_bytes(int64_t bytes) {
  char text[32];
  if (bytes >= (int64_t{1} << 30))
    std::snprintf(text, sizeof text, "%.2f GB", bytes / double(int64_t{1} << 30));
  else
    std::snprintf(text, sizeof text, "%.0f MB", bytes / double(1 << 20));
  return text;
}

void check_memory(int64_t needed, const std::string& what) {
  const int64_t available = available_memory_bytes();
  if (needed <= available) return;
  std::ostringstream msg;
  msg << what << " needs about " << format_bytes(needed) << " of memory, but only " << format_bytes(available)
      << " are available; close other programs or use a mesh with fewer vertices";
  throw OutOfMemory(msg.str());
}

}  // namespace gauss
