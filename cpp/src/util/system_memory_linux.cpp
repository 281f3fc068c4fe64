// system_memory.h on Linux (and the fallback for other Unix systems, where the /proc and cgroup
// files do not exist and only RLIMIT_AS is read):
//   available: the smallest of
//     - MemAvailable in /proc/meminfo (free memory plus what the kernel can reclaim),
//     - the address-space limit (RLIMIT_AS) minus the current virtual size,
//     - every enclosing cgroup's memory limit minus its usage (v2 memory.max, v1 memory.limit_in_bytes;
//       reclaimable file cache not counted as usage);
//   total: MemTotal in /proc/meminfo;
//   release: glibc's malloc_trim (other C libraries: nothing).
#include "gauss/util/system_memory.h"

#include <sys/resource.h>
#include <unistd.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <string>

namespace gauss {
namespace {

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

// The first number in a file ("max" and unreadable files: kUnknownMemory).
int64_t read_number(const std::string& path) {
  std::istringstream in(read_text(path));
  long double value;
  if (!(in >> value) || value < 0) return kUnknownMemory;
  return value >= static_cast<long double>(kUnknownMemory) ? kUnknownMemory : static_cast<int64_t>(value);
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

// A "Key: N kB" line of /proc/meminfo in bytes (kUnknownMemory if absent).
int64_t meminfo(const char* key) {
  std::istringstream in(read_text("/proc/meminfo"));
  const std::string prefix = std::string(key) + ":";
  std::string line;
  while (std::getline(in, line)) {
    long long kb;
    if (line.compare(0, prefix.size(), prefix) == 0 && std::sscanf(line.c_str() + prefix.size(), " %lld kB", &kb) == 1)
      return static_cast<int64_t>(kb) * 1024;
  }
  return kUnknownMemory;
}

int64_t address_space_left() {
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return kUnknownMemory;
  std::istringstream in(read_text("/proc/self/statm"));
  long long pages;
  if (!(in >> pages)) return kUnknownMemory;
  const int64_t used = static_cast<int64_t>(pages) * sysconf(_SC_PAGESIZE);
  return std::max<int64_t>(0, static_cast<int64_t>(limit.rlim_cur) - used);
}

// Limit minus usage of a cgroup folder and of every folder above it up to `root`.
int64_t cgroup_left(const std::string& root, std::string path, const char* limit_file, const char* usage_file,
                    const char* cache_key) {
  int64_t left = kUnknownMemory;
  while (true) {
    const std::string dir = root + path;
    const int64_t limit = read_number(dir + "/" + limit_file);
    if (limit != kUnknownMemory) {
      const int64_t usage = read_number(dir + "/" + usage_file);
      if (usage != kUnknownMemory) {
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
  int64_t left = kUnknownMemory;
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

int64_t system_available_memory_bytes() {
  return std::min({meminfo("MemAvailable"), address_space_left(), cgroups_left()});
}

int64_t system_total_memory_bytes() { return meminfo("MemTotal"); }

void release_free_memory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

}  // namespace gauss
