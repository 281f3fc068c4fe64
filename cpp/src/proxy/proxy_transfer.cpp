#include "gauss/proxy/proxy_transfer.h"

#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>

#include "gauss/util/parallel.h"

namespace gauss {

namespace {

// The orthonormal frame of triangle (a, b, c): its first edge, the in-plane axis, its normal; the
// identity for a triangle without area (its rotation then counts as none).
template <class Vec>
Eigen::Matrix3f frame(const Vec& a, const Vec& b, const Vec& c) {
  const Eigen::Vector3f e = (b - a).template cast<float>();
  const Eigen::Vector3f n = e.cross((c - a).template cast<float>());
  const float le = e.norm(), ln = n.norm();
  Eigen::Matrix3f m;
  if (!(le > 0.f) || !(ln > 0.f) || !std::isfinite(le) || !std::isfinite(ln)) return Eigen::Matrix3f::Identity();
  m.col(0) = e / le;
  m.col(2) = n / ln;
  m.col(1) = m.col(2).cross(m.col(0));
  return m;
}

template <class Scalar>
void transfer(ProxyTransfer& d, const Scalar* P, float* out) {
  const int np = d.num_proxy_vertices;
  const int ng = static_cast<int>(d.faces.size());
  const int nv = d.num_fine_vertices();
  parallel::for_ranges(np, parallel::kMinParallelItems, [&](int begin, int end) {
    for (int p = begin; p < end; ++p)
      d.proxy_position[p] = Eigen::Vector3f(static_cast<float>(P[3 * p]), static_cast<float>(P[3 * p + 1]),
                                            static_cast<float>(P[3 * p + 2]));
  });
  parallel::for_ranges(ng, parallel::kMinParallelItems, [&](int begin, int end) {
    for (int g = begin; g < end; ++g) {
      const auto& t = d.faces[g];
      const Eigen::Matrix3f R =
          frame(d.proxy_position[t[0]], d.proxy_position[t[1]], d.proxy_position[t[2]]) * d.rest_frame[g].transpose();
      const Eigen::Quaternionf q(R);
      d.face_rotation[g] = Eigen::Vector4f(q.w(), q.x(), q.y(), q.z());
    }
  });
  parallel::for_ranges(np, parallel::kMinParallelItems, [&](int begin, int end) {
    for (int p = begin; p < end; ++p) {
      Eigen::Vector4f sum = Eigen::Vector4f::Zero();
      const int first = d.vertex_face_start[p], last = d.vertex_face_start[p + 1];
      const Eigen::Vector4f& reference = first < last ? d.face_rotation[d.vertex_face[first]] : sum;
      for (int i = first; i < last; ++i) {
        const Eigen::Vector4f& q = d.face_rotation[d.vertex_face[i]];
        sum += (q.dot(reference) < 0.f ? -d.vertex_face_weight[i] : d.vertex_face_weight[i]) * q;  // q ~ -q
      }
      const float length = sum.norm();
      d.vertex_rotation[p] = length > 0.f && std::isfinite(length)
                                 ? Eigen::Quaternionf(sum[0] / length, sum[1] / length, sum[2] / length, sum[3] / length)
                                       .toRotationMatrix()
                                 : Eigen::Matrix3f::Identity();
    }
  });
  parallel::for_ranges(nv, parallel::kMinParallelItems, [&](int begin, int end) {
    for (int i = begin; i < end; ++i) {
      const Eigen::Map<const Eigen::Vector3f> offset(d.fine_offset[i].data());
      Eigen::Map<Eigen::Vector3f> x(out + 3 * static_cast<size_t>(i));
      const int g = d.fine_face[i];
      if (g < 0) {
        x = offset;
        continue;
      }
      const auto& t = d.faces[g];
      const float b1 = d.fine_bary[i][0], b2 = d.fine_bary[i][1], b0 = 1.f - b1 - b2;
      const Eigen::Matrix3f M = b0 * d.vertex_rotation[t[0]] + b1 * d.vertex_rotation[t[1]] +
                                b2 * d.vertex_rotation[t[2]];
      x = b0 * d.proxy_position[t[0]] + b1 * d.proxy_position[t[1]] + b2 * d.proxy_position[t[2]] + M * offset;
    }
  });
}

}  // namespace

ProxyTransfer proxy_transfer_precomputation(const ProxyMesh& proxy) {
  ProxyTransfer d;
  const int np = static_cast<int>(proxy.vertices.size());
  const int ng = static_cast<int>(proxy.faces.size());
  const size_t nv = proxy.fine_face.size();
  if (proxy.fine_bary.size() != nv || proxy.fine_offset.size() != nv)
    throw std::invalid_argument("the proxy's map has arrays of different lengths");
  for (const auto& t : proxy.faces)
    for (int k = 0; k < 3; ++k)
      if (t[k] < 0 || t[k] >= np) throw std::invalid_argument("a proxy face refers to a missing proxy vertex");
  for (int g : proxy.fine_face)
    if (g < -1 || g >= ng) throw std::invalid_argument("a fine vertex rides on a missing proxy face");
  d.num_proxy_vertices = np;
  d.faces = proxy.faces;
  d.rest_frame.resize(ng);
  std::vector<float> area(ng);
  for (int g = 0; g < ng; ++g) {
    const auto& t = proxy.faces[g];
    const Eigen::Vector3d &a = proxy.vertices[t[0]], &b = proxy.vertices[t[1]], &c = proxy.vertices[t[2]];
    d.rest_frame[g] = frame(a, b, c);
    area[g] = static_cast<float>(0.5 * (b - a).cross(c - a).norm());
  }
  d.vertex_face_start.assign(np + 1, 0);
  for (const auto& t : proxy.faces)
    for (int k = 0; k < 3; ++k) ++d.vertex_face_start[t[k] + 1];
  for (int p = 0; p < np; ++p) d.vertex_face_start[p + 1] += d.vertex_face_start[p];
  d.vertex_face.resize(d.vertex_face_start[np]);
  d.vertex_face_weight.resize(d.vertex_face_start[np]);
  std::vector<int> fill(d.vertex_face_start.begin(), d.vertex_face_start.end() - 1);
  for (int g = 0; g < ng; ++g)
    for (int k = 0; k < 3; ++k) {
      const int slot = fill[proxy.faces[g][k]]++;
      d.vertex_face[slot] = g;
      d.vertex_face_weight[slot] = area[g];
    }
  d.fine_face = proxy.fine_face;
  d.fine_bary = proxy.fine_bary;
  d.fine_offset = proxy.fine_offset;
  d.face_rotation.resize(ng);
  d.vertex_rotation.resize(np);
  d.proxy_position.resize(np);
  return d;
}

void proxy_transfer(ProxyTransfer& data, const float* P, float* out) { transfer(data, P, out); }
void proxy_transfer(ProxyTransfer& data, const double* P, float* out) { transfer(data, P, out); }

}  // namespace gauss
