#pragma once
// numpy arrays <-> the flat vectors and Eigen types the solver takes, for the Python module only.
// Every reader checks dtype and shape and raises TypeError/ValueError naming the argument, and accepts
// any strides and any real dtype (Blender's float32/int32 included) without a copy on the Python side.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <sstream>
#include <string>
#include <vector>

namespace gauss_python {

namespace py = pybind11;

// Reads an (n, cols) array of any real dtype and any strides into a flat row-major vector.
template <typename Out>
std::vector<Out> read_matrix(const py::handle& obj, py::ssize_t cols, const char* name, bool integer) {
  py::array arr = py::array::ensure(obj);
  if (!arr) throw py::type_error(std::string(name) + " must be array-like");
  const char kind = arr.dtype().kind();
  const bool ok_kind = integer ? (kind == 'i' || kind == 'u') : (kind == 'f' || kind == 'i' || kind == 'u');
  if (!ok_kind) {
    std::ostringstream msg;
    msg << name << " must have a" << (integer ? "n integer" : " floating-point") << " dtype, got " << py::str(arr.dtype()).cast<std::string>();
    throw py::type_error(msg.str());
  }
  if (arr.ndim() == 1 && cols == 1) {
  } else if (arr.ndim() != 2 || arr.shape(1) != cols) {
    std::ostringstream msg;
    msg << name << " must have shape (n, " << cols << "), got (";
    for (py::ssize_t i = 0; i < arr.ndim(); ++i) msg << (i ? ", " : "") << arr.shape(i);
    msg << (arr.ndim() == 1 ? ",)" : ")");
    throw py::value_error(msg.str());
  }
  // Convert through numpy only when the dtype differs; float32/int32 from Blender take this path
  // inside native code, the caller never copies.
  py::array_t<Out, py::array::forcecast> typed(arr);
  std::vector<Out> out(static_cast<size_t>(typed.size()));
  if (cols == 1 && typed.ndim() == 1) {
    auto r = typed.template unchecked<1>();
    for (py::ssize_t i = 0; i < r.shape(0); ++i) out[i] = r(i);
  } else {
    auto r = typed.template unchecked<2>();
    for (py::ssize_t i = 0; i < r.shape(0); ++i)
      for (py::ssize_t j = 0; j < cols; ++j) out[i * cols + j] = r(i, j);
  }
  return out;
}

inline Eigen::Matrix3d read_rotation(const py::object& obj) {
  if (obj.is_none()) return Eigen::Matrix3d::Identity();
  std::vector<double> m = read_matrix<double>(obj, 3, "rotation", false);
  if (m.size() != 9) throw py::value_error("rotation must be a 3x3 matrix");
  Eigen::Matrix3d R;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R(i, j) = m[3 * i + j];
  return R;
}

// py::array::ensure returns a null handle (numpy's error cleared) for ragged lists and the like.
inline py::array as_array(const py::handle& obj, const char* name) {
  py::array arr = py::array::ensure(obj);
  if (!arr) throw py::type_error(std::string(name) + " must be array-like");
  return arr;
}

inline Eigen::Vector3d read_vector3(const py::object& obj, const char* name) {
  std::vector<double> v = read_matrix<double>(as_array(obj, name).reshape({1, -1}), 3, name, false);
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

inline py::array_t<double> to_array(const std::vector<Eigen::Vector3d>& v) {
  py::array_t<double> out({static_cast<py::ssize_t>(v.size()), py::ssize_t(3)});
  auto w = out.mutable_unchecked<2>();
  for (size_t i = 0; i < v.size(); ++i)
    for (int k = 0; k < 3; ++k) w(i, k) = v[i][k];
  return out;
}

// Evaluates f at one point (shape (3,)) or many (shape (n, 3)).
template <typename F>
py::object eval_points(const py::object& x, F&& f) {
  py::array arr = py::array::ensure(x);
  if (!arr) throw py::type_error("x must be array-like");
  const bool single = arr.ndim() == 1;
  std::vector<double> pts = read_matrix<double>(single ? arr.reshape({1, -1}) : arr, 3, "x", false);
  return f(pts, single);
}

}  // namespace gauss_python
