#pragma once
// The module refuses to load under a numpy whose arrays the pybind11 it was built with cannot read.
//
// numpy 2 moved fields of its dtype struct; pybind11 reads them at the new offsets from 2.12 on. A
// module built with an older pybind11 (e.g. Debian 12's 2.10) and imported beside numpy 2 reads every
// dtype's item size as 0 and its flags as garbage: array checks pass or fail at random and a division
// by the item size crashes the process (Blender, with the artist's unsaved work). So at import, before
// any array is touched, such a module compares numpy's major version with what its pybind11 reads and
// raises ImportError, which the add-on turns into its readable message (native.py). Builds with the
// pinned pybind11 (pyproject.toml) read numpy 1.x and 2.x and never refuse.
// tests/python/test_numpy_mismatch.py builds a module with pybind11 2.10 and imports it under numpy 2.
#include <pybind11/pybind11.h>

#include <string>

namespace gauss_python {

// The newest numpy major the pybind11 this module is compiled with can read.
constexpr int kNewestReadableNumpyMajor =
    (PYBIND11_VERSION_MAJOR > 2 || (PYBIND11_VERSION_MAJOR == 2 && PYBIND11_VERSION_MINOR >= 12)) ? 2 : 1;

// Throws ImportError (pybind11::import_error) if the running numpy is newer than that; a missing or
// unparsable numpy is left to the first array call's own error.
inline void refuse_unreadable_numpy() {
  namespace py = pybind11;
  std::string version;
  try {
    version = py::module_::import("numpy").attr("__version__").cast<std::string>();
  } catch (const py::error_already_set&) {
    return;
  }
  int major = 0;
  for (char c : version) {
    if (c < '0' || c > '9') break;
    major = major * 10 + (c - '0');
  }
  if (major > kNewestReadableNumpyMajor) {
    throw py::import_error(
        "gauss_core was built with pybind11 " + std::to_string(PYBIND11_VERSION_MAJOR) + "." +
        std::to_string(PYBIND11_VERSION_MINOR) + ", which reads numpy " +
        std::to_string(kNewestReadableNumpyMajor) + ".x arrays only, and this Python runs numpy " + version +
        ": it refuses to load rather than misread arrays. Rebuild it with the pybind11 pinned in "
        "pyproject.toml (2.12 or newer reads numpy 1.x and 2.x).");
  }
}

}  // namespace gauss_python
