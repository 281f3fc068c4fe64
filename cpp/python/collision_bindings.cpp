// Binding of gauss_core.self_intersections: which faces of a mesh pass through each other, counted as
// Blender's 3D-Print toolbox counts them (self_intersection.h), for a result's check and for showing
// the pairs in red.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <cmath>
#include <sstream>
#include <vector>

#include "gauss/collision/self_intersection.h"
#include "module_parts.h"
#include "numpy_arrays.h"

namespace gauss_python {

namespace py = pybind11;

void bind_self_intersections(py::module_& m) {
  m.def("self_intersections", [](const py::object& V, const py::object& F) {
        const std::vector<double> v = read_matrix<double>(V, 3, "V", false);
        const std::vector<int64_t> f = read_matrix<int64_t>(F, 3, "F", true);
        const int64_t nV = static_cast<int64_t>(v.size() / 3);
        for (size_t i = 0; i < v.size(); ++i)
          if (!std::isfinite(v[i])) {
            std::ostringstream msg;
            msg << "vertex " << i / 3 << " has a NaN or infinite coordinate";
            throw py::value_error(msg.str());
          }
        std::vector<std::array<int, 3>> faces;
        std::vector<int64_t> input_face;  // the caller's index of each face kept
        for (size_t i = 0; i < f.size() / 3; ++i) {
          const int64_t* t = &f[3 * i];
          for (int k = 0; k < 3; ++k)
            if (t[k] < 0 || t[k] >= nV) {
              std::ostringstream msg;
              msg << "face " << i << " refers to vertex " << t[k] << "; valid: 0 to " << nV - 1;
              throw py::value_error(msg.str());
            }
          if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;  // no area: crosses nothing
          faces.push_back({static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2])});
          input_face.push_back(static_cast<int64_t>(i));
        }
        std::vector<Eigen::Vector3d> X(nV);
        for (int64_t i = 0; i < nV; ++i) X[i] = Eigen::Vector3d(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
        std::vector<std::array<int, 2>> pairs;
        {
          py::gil_scoped_release release;
          pairs = gauss::self_intersecting_pairs(faces, X);
        }
        py::array_t<int64_t> out({static_cast<py::ssize_t>(pairs.size()), static_cast<py::ssize_t>(2)});
        auto o = out.mutable_unchecked<2>();
        for (size_t i = 0; i < pairs.size(); ++i) {
          o(i, 0) = input_face[pairs[i][0]];
          o(i, 1) = input_face[pairs[i][1]];
        }
        return out;
      },
      py::arg("V"), py::arg("F"),
      R"doc(The pairs of faces that pass through each other: (#P, 2) int64, each pair once (f < g).

V: (#V, 3) vertex positions; F: (#F, 3) vertex indices (faces with a repeated index are skipped).
Two faces cross when they meet along a segment of positive length; meeting in a shared corner or edge,
or lying in one plane, is not crossing (as Blender's BVHTree.overlap of a mesh with itself counts,
which lists every pair twice). Raises ValueError on NaN coordinates or indices out of range.)doc");
}

}  // namespace gauss_python
