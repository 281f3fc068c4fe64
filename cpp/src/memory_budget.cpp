#include "gauss/memory_budget.h"

#include <sys/resource.h>
#include <unistd.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>

namespace gauss {
namespace {

constexpr int64_t kUnknown = std::numeric_limits<int64_t>::max();

// A small text file's content ("" if unreadable). Read with C stdio, not file streams: libstdc++'s
// file streams reference fstat64@GLIBC_2.33, which would keep the module from loading on glibc 2.28
// (tests/python/test_module_reach.py).
std::string read_text(const std::string& path) {
  std::string text;
  if (FILE* f = std::fopen(path.c_str(), "r")) {
    char buffer[4096];
    size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) text.append(buffer, n);
    std::fclose(f);
  }
  return text;
}

// The first number in a file ("max" and unreadable files: kUnknown).
int64_t read_number(const std::string& path) {
  std::istringstream in(read_text(path));
  long double value;
  if (!(in >> value) || value < 0) return kUnknown;
  return value >= static_cast<long double>(kUnknown) ? kUnknown : static_cast<int64_t>(value);
}

// The value of `key` in a "key value" file (memory.stat), 0 if absent.
int64_t read_key(const std::string& path, const std::string& key) {
  std::istringstream in(read_text(path));
  std::string k;
  long long v;
  while (in >> k >> v)
    if (k == key) return v;
  return 0;
}

int64_t meminfo_available() {
  std::istringstream in(read_text("/proc/meminfo"));
  std::string line;
  while (std::getline(in, line)) {
    long long kb;
    if (std::sscanf(line.c_str(), "MemAvailable: %lld kB", &kb) == 1) return static_cast<int64_t>(kb) * 1024;
  }
  return kUnknown;
}

int64_t address_space_left() {
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return kUnknown;
  std::istringstream in(read_text("/proc/self/statm"));
  long long pages;
  if (!(in >> pages)) return kUnknown;
  const int64_t used = static_cast<int64_t>(pages) * sysconf(_SC_PAGESIZE);
  return std::max<int64_t>(0, static_cast<int64_t>(limit.rlim_cur) - used);
}

// Limit minus usage of a cgroup folder and of every folder above it up to `root`.
int64_t cgroup_left(const std::string& root, std::string path, const char* limit_file, const char* usage_file,
                    const char* cache_key) {
  int64_t left = kUnknown;
  while (true) {
    const std::string dir = root + path;
    const int64_t limit = read_number(dir + "/" + limit_file);
    if (limit != kUnknown) {
      const int64_t usage = read_number(dir + "/" + usage_file);
      if (usage != kUnknown) {
        const int64_t cache = read_key(dir + "/memory.stat", cache_key);
        left = std::min(left, std::max<int64_t>(0, limit - std::max<int64_t>(0, usage - cache)));
      }
    }
    if (path.empty() || path == "/") break;
    const size_t slash = path.find_last_of('/');
    path = slash == std::string::npos ? "" : path.substr(0, slash);
  }
  return left;
}

int64_t cgroups_left() {
  std::istringstream in(read_text("/proc/self/cgroup"));
  std::string line;
  int64_t left = kUnknown;
  while (std::getline(in, line)) {
    // "hierarchy-id:controllers:path"; v2 has the empty controller list.
    const size_t a = line.find(':'), b = line.find(':', a + 1);
    if (a == std::string::npos || b == std::string::npos) continue;
    const std::string controllers = line.substr(a + 1, b - a - 1), path = line.substr(b + 1);
    if (controllers.empty()) {
      left = std::min(left, cgroup_left("/sys/fs/cgroup", path, "memory.max", "memory.current", "inactive_file"));
    } else if (("," + controllers + ",").find(",memory,") != std::string::npos) {
      left = std::min(left, cgroup_left("/sys/fs/cgroup/memory", path, "memory.limit_in_bytes",
                                        "memory.usage_in_bytes", "total_inactive_file"));
    }
  }
  return left;
}

}  // namespace

int64_t available_memory_bytes() {
  if (const char* budget = std::getenv("GAUSS_MEMORY_BUDGET_MB")) {
    char* end = nullptr;
    const double mb = std::strtod(budget, &end);
    if (end != budget && mb >= 0 && mb < 1e12) return static_cast<int64_t>(mb * 1024 * 1024);
  }
  return std::min({meminfo_available(), address_space_left(), cgroups_left()});
}

void release_free_memory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
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
