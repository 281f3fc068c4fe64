#pragma once
// Sets an environment variable for the lifetime of the object, as the C runtime's getenv sees it
// (POSIX setenv/unsetenv; Windows has neither: _putenv_s, where the empty value unsets).
#include <cstdlib>
#include <string>

namespace gauss_test {

class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old, had_ = true;
    set(name, value);
  }
  ~ScopedEnv() {
    if (had_) set(name_, old_.c_str());
    else unset(name_);
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
#if defined(_WIN32)
  static void set(const char* name, const char* value) { _putenv_s(name, value); }
  static void unset(const char* name) { _putenv_s(name, ""); }
#else
  static void set(const char* name, const char* value) { setenv(name, value, 1); }
  static void unset(const char* name) { unsetenv(name); }
#endif

  const char* name_;
  std::string old_;
  bool had_ = false;
};

}  // namespace gauss_test
