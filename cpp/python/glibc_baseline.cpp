// Keeps the Python module loadable on glibc 2.28 (what official Blender builds target) although it is
// built against a newer glibc (Debian 12: 2.36). Linked into gauss_core only (CMakeLists.txt, "Reach"
// block); the solver library, the benchmark and the tests do not need it.
//
// A shared object records, for every glibc function it calls, the symbol version that was the default
// when it was linked; an older glibc lacks the newer versions and refuses to load it. The module's own
// code and the C++ runtime linked into it (libstdc++.a, libgcc_eh.a) reference seven such symbols, so
// this file defines them: every reference in the module binds to these definitions, and the version
// script makes them local, so nothing outside the module sees them.
//
//  - exp: 2.29 gave it a new version (same values, no SVID error handling, and on x86-64 an
//    implementation chosen for the CPU: the old version is slower in the preference function, see
//    docs/building.md, "Why not zig instead"). The first call therefore looks exp@GLIBC_2.29 up with
//    dlvsym and uses it where it exists, i.e. the very function the module would otherwise have been
//    linked to; an older glibc gets its GLIBC_2.2.5 version, the only one it has. The solver needs the
//    value, never errno.
//  - pthread_create, pthread_detach, pthread_once, __pthread_key_create: 2.34 moved libpthread (and
//    libdl) into libc under new versions. Forwarded to the GLIBC_2.2.5 versions, the same functions,
//    which libc keeps for old binaries and which glibc < 2.34 has in libpthread.so.0; dlvsym, used for
//    exp, likewise (libdl.so.2). The module lists both libraries as NEEDED so they are always loaded.
//  - __libc_single_threaded (2.32): libstdc++ skips atomic reference counting when it is true. This
//    copy is always false, which is always correct; it only costs the atomics in a single-threaded
//    process, and Blender never is one.
//  - _dl_find_object (2.35): the unwinder (libgcc_eh.a) finds the unwind tables of the code an
//    exception passes through with it, and has no fallback. This replacement finds them with
//    dl_iterate_phdr (glibc 2.2.5), as libgcc did before GCC 12; it only runs when an exception is
//    thrown, i.e. when the module rejects bad input.
//
// tests/python/test_module_reach.py fails when the module references any other version newer than
// GLIBC_2.28. The symbol version names are x86-64's, so CMake compiles this file only there (without
// LTO: the .symver directives must land in the same object as the references they rename).

#ifndef _GNU_SOURCE
#define _GNU_SOURCE 1  // _dl_find_object, dl_iterate_phdr, RTLD_DEFAULT
#endif
#include <dlfcn.h>
#include <link.h>
#include <math.h>
#include <pthread.h>
#include <sys/single_threaded.h>

#include <atomic>
#include <cstdint>

#if !defined(__x86_64__) || !defined(__GLIBC__)
#error "glibc_baseline.cpp binds x86-64 glibc symbol versions; build it only for x86-64 Linux (glibc)"
#endif

// gauss_glibc_NAME: a reference to NAME@GLIBC_2.2.5, x86-64's oldest version of every glibc symbol.
#define GAUSS_OLDEST_VERSION_OF(name) __asm__(".symver gauss_glibc_" #name ", " #name "@GLIBC_2.2.5")

extern "C" {

double gauss_glibc_exp(double x) noexcept;
void* gauss_glibc_dlvsym(void* handle, const char* name, const char* version);
int gauss_glibc_pthread_create(pthread_t* thread, const pthread_attr_t* attributes,
                               void* (*start)(void*), void* argument);
int gauss_glibc_pthread_detach(pthread_t thread);
int gauss_glibc_pthread_once(pthread_once_t* once, void (*init)());
int gauss_glibc___pthread_key_create(pthread_key_t* key, void (*destructor)(void*));
GAUSS_OLDEST_VERSION_OF(exp);
GAUSS_OLDEST_VERSION_OF(dlvsym);
GAUSS_OLDEST_VERSION_OF(pthread_create);
GAUSS_OLDEST_VERSION_OF(pthread_detach);
GAUSS_OLDEST_VERSION_OF(pthread_once);
GAUSS_OLDEST_VERSION_OF(__pthread_key_create);

}  // extern "C"

namespace {

using Exp = double (*)(double) noexcept;
double exp_on_first_call(double x) noexcept;
// Constant-initialized, so usable before any static constructor ran; after the first call it holds
// the chosen exp, and every call is one indirect jump, like a call through the PLT.
std::atomic<Exp> chosen_exp{&exp_on_first_call};

double exp_on_first_call(double x) noexcept {
  // RTLD_DEFAULT searches the module's own dependencies (libm) too. Threads that race here store the
  // same pointer.
  void* current = gauss_glibc_dlvsym(RTLD_DEFAULT, "exp", "GLIBC_2.29");
  const Exp chosen = current != nullptr ? reinterpret_cast<Exp>(current) : &gauss_glibc_exp;
  chosen_exp.store(chosen, std::memory_order_relaxed);
  return chosen(x);
}

}  // namespace

extern "C" {

// The signatures are checked against glibc's own declarations (a mismatch does not compile).
double exp(double x) noexcept { return chosen_exp.load(std::memory_order_relaxed)(x); }

int pthread_create(pthread_t* thread, const pthread_attr_t* attributes, void* (*start)(void*),
                   void* argument) noexcept {
  return gauss_glibc_pthread_create(thread, attributes, start, argument);
}

int pthread_detach(pthread_t thread) noexcept { return gauss_glibc_pthread_detach(thread); }

int pthread_once(pthread_once_t* once, void (*init)()) { return gauss_glibc_pthread_once(once, init); }

// Not declared by any header: libstdc++ references it (weakly) to find out whether threads exist.
int __pthread_key_create(pthread_key_t* key, void (*destructor)(void*)) noexcept;
int __pthread_key_create(pthread_key_t* key, void (*destructor)(void*)) noexcept {
  return gauss_glibc___pthread_key_create(key, destructor);
}

char __libc_single_threaded = 0;

}  // extern "C"

namespace {

struct FindRequest {
  std::uintptr_t address;
  dl_find_object* result;
};

// dl_iterate_phdr callback: 1 (stop) once the loaded object whose segments contain the address is found.
int find_object_containing(dl_phdr_info* info, size_t, void* data) {
  FindRequest& request = *static_cast<FindRequest*>(data);
  std::uintptr_t map_start = UINTPTR_MAX, map_end = 0;
  void* eh_frame = nullptr;
  bool contains = false;
  for (int i = 0; i < info->dlpi_phnum; ++i) {
    const ElfW(Phdr)& segment = info->dlpi_phdr[i];
    const std::uintptr_t start = info->dlpi_addr + segment.p_vaddr;
    if (segment.p_type == PT_LOAD) {
      const std::uintptr_t end = start + segment.p_memsz;
      if (start < map_start) map_start = start;
      if (end > map_end) map_end = end;
      if (request.address >= start && request.address < end) contains = true;
    } else if (segment.p_type == PT_GNU_EH_FRAME) {
      eh_frame = reinterpret_cast<void*>(start);
    }
  }
  if (!contains) return 0;
  *request.result = dl_find_object{};
  request.result->dlfo_map_start = reinterpret_cast<void*>(map_start);
  request.result->dlfo_map_end = reinterpret_cast<void*>(map_end);
  request.result->dlfo_link_map = nullptr;  // not available here; the unwinder does not read it
  request.result->dlfo_eh_frame = eh_frame;
  return 1;
}

}  // namespace

// Same contract as glibc's: 0 and *result filled if a loaded object contains address, else -1.
extern "C" int _dl_find_object(void* address, dl_find_object* result) noexcept {
  FindRequest request{reinterpret_cast<std::uintptr_t>(address), result};
  return dl_iterate_phdr(find_object_containing, &request) != 0 ? 0 : -1;
}
