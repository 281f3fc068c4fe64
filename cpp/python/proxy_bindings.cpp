// Binding of gauss_core.Proxy: a simplified copy of a large mesh that a live run stylizes, and the
// transfer of its deformation back to the full mesh at every tick (proxy_mesh.h, proxy_transfer.h).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <mutex>
#include <sstream>
#include <vector>

#include "gauss/proxy/proxy_mesh.h"
#include "gauss/proxy/proxy_transfer.h"
#include "module_parts.h"
#include "numpy_arrays.h"

namespace gauss_python {

namespace py = pybind11;

namespace {

class Proxy {
 public:
  Proxy(const py::object& V, const py::object& F, int target_vertices) {
    const std::vector<double> v = read_matrix<double>(V, 3, "V", false);
    const std::vector<int64_t> f = read_matrix<int64_t>(F, 3, "F", true);
    if (v.size() / 3 > static_cast<size_t>(INT32_MAX) || f.size() / 3 > static_cast<size_t>(INT32_MAX))
      throw py::value_error("the mesh has more than 2^31 vertices or faces");
    py::gil_scoped_release release;
    mesh_ = gauss::proxy_mesh(v.data(), static_cast<int>(v.size() / 3), f.data(), static_cast<int>(f.size() / 3),
                              target_vertices);
    transfer_ = gauss::proxy_transfer_precomputation(mesh_);
  }

  py::array_t<double> vertices() const {
    py::array_t<double> out({static_cast<py::ssize_t>(mesh_.vertices.size()), py::ssize_t(3)});
    auto w = out.mutable_unchecked<2>();
    for (size_t i = 0; i < mesh_.vertices.size(); ++i)
      for (int k = 0; k < 3; ++k) w(i, k) = mesh_.vertices[i][k];
    return out;
  }

  py::array_t<int32_t> triangles() const {
    py::array_t<int32_t> out({static_cast<py::ssize_t>(mesh_.faces.size()), py::ssize_t(3)});
    auto w = out.mutable_unchecked<2>();
    for (size_t i = 0; i < mesh_.faces.size(); ++i)
      for (int k = 0; k < 3; ++k) w(i, k) = mesh_.faces[i][k];
    return out;
  }

  py::array_t<int32_t> fine_of_proxy() const {
    py::array_t<int32_t> out(static_cast<py::ssize_t>(mesh_.fine_of_proxy.size()));
    std::copy(mesh_.fine_of_proxy.begin(), mesh_.fine_of_proxy.end(), out.mutable_data());
    return out;
  }

  py::tuple fine_map() const {
    const py::ssize_t n = static_cast<py::ssize_t>(mesh_.fine_face.size());
    py::array_t<int32_t> face(n);
    py::array_t<float> bary({n, py::ssize_t(2)}), offset({n, py::ssize_t(3)});
    std::copy(mesh_.fine_face.begin(), mesh_.fine_face.end(), face.mutable_data());
    std::copy(&mesh_.fine_bary[0][0], &mesh_.fine_bary[0][0] + 2 * n, bary.mutable_data());
    std::copy(&mesh_.fine_offset[0][0], &mesh_.fine_offset[0][0] + 3 * n, offset.mutable_data());
    return py::make_tuple(face, bary, offset);
  }

  int num_fine_vertices() const { return transfer_.num_fine_vertices(); }

  void transfer(const py::array& proxy_vertices, const py::array& out) {
    const py::ssize_t np = static_cast<py::ssize_t>(mesh_.vertices.size());
    const py::ssize_t nv = transfer_.num_fine_vertices();
    check_buffer(proxy_vertices, np, "proxy_vertices", false);
    check_buffer(out, nv, "out", true);
    if (!out.dtype().is(py::dtype::of<float>())) throw py::type_error("out must have dtype float32");
    float* target = static_cast<float*>(const_cast<void*>(out.data()));
    if (proxy_vertices.dtype().is(py::dtype::of<float>())) {
      const float* source = static_cast<const float*>(proxy_vertices.data());
      py::gil_scoped_release release;
      std::lock_guard<std::mutex> lock(mutex_);
      gauss::proxy_transfer(transfer_, source, target);
    } else if (proxy_vertices.dtype().is(py::dtype::of<double>())) {
      const double* source = static_cast<const double*>(proxy_vertices.data());
      py::gil_scoped_release release;
      std::lock_guard<std::mutex> lock(mutex_);
      gauss::proxy_transfer(transfer_, source, target);
    } else {
      throw py::type_error("proxy_vertices must have dtype float32 or float64");
    }
  }

 private:
  // (n, 3) or (3n,), C-contiguous and aligned (and writeable for an output): read and written in place.
  static void check_buffer(const py::array& a, py::ssize_t n, const char* name, bool writeable) {
    const bool shape_ok = (a.ndim() == 2 && a.shape(0) == n && a.shape(1) == 3) || (a.ndim() == 1 && a.shape(0) == 3 * n);
    if (!shape_ok) {
      std::ostringstream msg;
      msg << name << " must have shape (" << n << ", 3) or (" << 3 * n << ",)";
      throw py::value_error(msg.str());
    }
    if (!(a.flags() & py::array::c_style) || (writeable && !a.writeable()))
      throw py::value_error(std::string(name) + (writeable ? " must be a writeable" : " must be a") + " C-contiguous array");
    if (a.itemsize() <= 0 ||
        reinterpret_cast<std::uintptr_t>(a.data()) % static_cast<std::uintptr_t>(a.itemsize()) != 0)
      throw py::value_error(std::string(name) + " must be an aligned array");
  }

  gauss::ProxyMesh mesh_;
  gauss::ProxyTransfer transfer_;
  std::mutex mutex_;  // one transfer at a time: it writes the proxy's scratch
};

}  // namespace

void bind_proxy(py::module_& m) {
  py::class_<Proxy>(m, "Proxy", R"doc(
A simplified copy of a large mesh for live runs, and the map that carries its deformation back.

Proxy(V, F, target_vertices)
  V: (#V, 3) rest positions; F: (#F, 3) vertex indices (faces with a repeated index are skipped).
  target_vertices >= 4: the proxy's size (fewer vertices are never made; more remain where no
  collapse keeps the surface manifold). Half-edge collapses by quadric error, so flat parts
  simplify first, silhouettes and creases last, and boundaries keep their outline; every proxy vertex
  is a vertex of the mesh. Raises ValueError on NaN positions, indices out of range or no usable face.
  Releases the GIL.

vertices          (#P, 3) float64: the proxy's rest positions (solve on these with `triangles`)
triangles         (#G, 3) int32: its faces
fine_of_proxy     (#P,) int32: the mesh vertex each proxy vertex is
fine_map          (face (#V,) int32, bary (#V, 2) float32, offset (#V, 3) float32): the proxy face each
                  mesh vertex rides on (-1: in no face; it stays at offset), the weights of that face's
                  corners 1 and 2, the offset from that point to the vertex at rest
num_fine_vertices #V
transfer(proxy_vertices, out)
                  the mesh's vertices for the proxy deformed to proxy_vertices ((#P, 3) float32 or
                  float64), written into out ((#V, 3) or (3 #V,) float32, C-contiguous): each vertex at its
                  point of the deformed face plus its offset turned by the face corners' rotations, so
                  detail turns with the surface. Allocates nothing; releases the GIL; runs on the
                  solver's threads.)doc")
      .def(py::init<const py::object&, const py::object&, int>(), py::arg("V"), py::arg("F"),
           py::arg("target_vertices"))
      .def_property_readonly("vertices", &Proxy::vertices)
      .def_property_readonly("triangles", &Proxy::triangles)
      .def_property_readonly("fine_of_proxy", &Proxy::fine_of_proxy)
      .def_property_readonly("fine_map", &Proxy::fine_map)
      .def_property_readonly("num_fine_vertices", &Proxy::num_fine_vertices)
      .def("transfer", &Proxy::transfer, py::arg("proxy_vertices"), py::arg("out"));
}

}  // namespace gauss_python
