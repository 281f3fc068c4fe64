// The self-intersection guard's shortcuts (self_intersection.h, face_bvh.h) against brute force: the
// guard skips the pairs around a corner whose star is flat, judges pairs that share corners by crossing
// alone (an edge: never), and skips the pairs inside a flat patch of its hierarchy. Whatever it skips,
// its decision must be the one a test of every pair of faces with the guard's own contact rules gives:
// a candidate state with a new contact is held back until none is left, one without is left as it is.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "gauss/collision/self_intersection.h"
#include "gauss/collision/triangle_intersection.h"
#include "gauss/mesh/mesh_io.h"
#include "gauss/mesh/mesh_topology.h"
#include "gauss/util/parallel.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_self_intersection_shortcuts {

using Eigen::Vector3d;
using gauss::Triangle;

namespace {

using Faces = std::vector<std::array<int, 3>>;
using Points = std::vector<Vector3d>;

struct Mesh {
  Faces faces;
  Points X;
};

Mesh mesh_of(const gauss::TriangleMesh& m) {
  Mesh out;
  for (int i = 0; i < m.num_faces(); ++i)
    out.faces.push_back({static_cast<int>(m.F[3 * i]), static_cast<int>(m.F[3 * i + 1]), static_cast<int>(m.F[3 * i + 2])});
  for (int v = 0; v < m.num_vertices(); ++v) out.X.emplace_back(m.V[3 * v], m.V[3 * v + 1], m.V[3 * v + 2]);
  return out;
}

gauss::MeshTopology topology_of(const Mesh& m) {
  std::vector<int64_t> F;
  for (const auto& f : m.faces) F.insert(F.end(), f.begin(), f.end());
  return gauss::build_mesh_topology(static_cast<int>(m.X.size()), F.data(), static_cast<int>(m.faces.size()));
}

// Scaled about the bounding box's centre so that its longest side is `size`.
void scale_to(Points& X, double size) {
  Vector3d lo = X[0], hi = X[0];
  for (const Vector3d& p : X) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const Vector3d centre = 0.5 * (lo + hi);
  const double s = size / (hi - lo).maxCoeff();
  for (Vector3d& p : X) p = (p - centre) * s;
}

// ---- Brute force: every pair of faces, with the rules self_intersection.h states. ----

// How many corners the faces share, and their corners with the shared ones first, in the same order.
int arranged(const std::array<int, 3>& fa, const std::array<int, 3>& fb, const Points& X, Triangle& a, Triangle& b) {
  std::array<int, 3> p = fa, q = fb;
  int shared = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = shared; j < 3; ++j)
      if (p[i] == q[j] && i >= shared) {
        std::swap(p[i], p[shared]);
        std::swap(q[j], q[shared]);
        ++shared;
        break;
      }
  for (int i = 0; i < 3; ++i) a.col(i) = X[p[i]], b.col(i) = X[q[i]];
  return shared;
}

bool crosses(const Faces& F, const Points& X, int f, int g) {
  Triangle a, b;
  const int shared = arranged(F[f], F[g], X, a, b);
  return gauss::triangles_cross(a, b, shared);
}

// In contact: sharing an edge, never; sharing a corner, when they cross; sharing none, when they cross
// or come closer than the margin (the start's own, kStartMargin, when the start's contacts are found).
bool in_contact(const Faces& F, const Points& X, int f, int g, double margin) {
  Triangle a, b;
  const int shared = arranged(F[f], F[g], X, a, b);
  if (shared >= 2) return false;
  if (shared == 1) return gauss::triangles_cross(a, b, 1);
  return gauss::triangles_closer_than(a, b, 0, margin);
}

uint64_t key(int f, int g) { return (static_cast<uint64_t>(std::min(f, g)) << 32) | static_cast<uint32_t>(std::max(f, g)); }

// Every pair in contact at X (sorted keys). Faces are taken in the order of their boxes' low x, so that
// the pairs skipped are those farther apart along x than the margin.
std::vector<uint64_t> contacts(const Faces& F, const Points& X, double margin = gauss::kContactMargin) {
  const int n = static_cast<int>(F.size());
  std::vector<Vector3d> lo(n), hi(n);
  std::vector<int> order(n);
  for (int f = 0; f < n; ++f) {
    lo[f] = X[F[f][0]].cwiseMin(X[F[f][1]]).cwiseMin(X[F[f][2]]);
    hi[f] = X[F[f][0]].cwiseMax(X[F[f][1]]).cwiseMax(X[F[f][2]]);
    order[f] = f;
  }
  std::sort(order.begin(), order.end(), [&](int f, int g) { return lo[f].x() < lo[g].x(); });
  std::vector<uint64_t> out;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n && lo[order[j]].x() <= hi[order[i]].x() + margin; ++j) {
      const int f = order[i], g = order[j];
      if (((lo[f] - hi[g]).array() > margin).any() || ((lo[g] - hi[f]).array() > margin).any()) continue;
      if (in_contact(F, X, f, g, margin)) out.push_back(key(f, g));
    }
  std::sort(out.begin(), out.end());
  return out;
}

// The start's rules: a pair in contact at the start (closer than kStartMargin, but kContactMargin next
// to a crossing) may stay so (if it only touched there, it may not
// cross), a pair next to a crossing of the start may cross (the crossing slides on), any other pair
// in contact is new.
struct Start {
  const Faces& F;
  std::vector<uint64_t> touching, crossing;
  std::vector<std::vector<int>> faces_at;  // #V: the faces around each vertex

  Start(const Faces& faces, const Points& S) : F(faces) {
    const std::vector<uint64_t> near = contacts(faces, S, gauss::kStartMargin);
    for (uint64_t k : near)
      if (crosses(F, S, static_cast<int>(k >> 32), static_cast<int>(k & 0xffffffffu))) crossing.push_back(k);
    int nV = 0;
    for (const auto& f : F) nV = std::max({nV, f[0] + 1, f[1] + 1, f[2] + 1});
    faces_at.resize(nV);
    for (int f = 0; f < static_cast<int>(F.size()); ++f)
      for (int v : F[f]) faces_at[v].push_back(f);
    // Only a hair apart (within kStartMargin, not kContactMargin) and next to a crossing: not touching,
    // a pair the crossing may slide onto.
    for (uint64_t k : near) {
      const int f = static_cast<int>(k >> 32), g = static_cast<int>(k & 0xffffffffu);
      if (std::binary_search(crossing.begin(), crossing.end(), k) || in_contact(F, S, f, g, gauss::kContactMargin) ||
          !next_to_crossing(f, g))
        touching.push_back(k);
    }
  }
  bool next_to_crossing(int f, int g) const {
    for (int v : F[f])
      for (int f0 : faces_at[v])
        for (int w : F[g])
          for (int g0 : faces_at[w])
            if (std::binary_search(crossing.begin(), crossing.end(), key(f0, g0))) return true;
    return false;
  }
  // The pairs in a contact at X that the start does not allow.
  std::vector<uint64_t> new_contacts(const Points& X) const {
    std::vector<uint64_t> out;
    for (uint64_t k : contacts(F, X)) {
      const int f = static_cast<int>(k >> 32), g = static_cast<int>(k & 0xffffffffu);
      if (std::binary_search(crossing.begin(), crossing.end(), k)) continue;
      if (std::binary_search(touching.begin(), touching.end(), k) && !crosses(F, X, f, g)) continue;
      if (next_to_crossing(f, g)) continue;
      out.push_back(k);
    }
    return out;
  }
};

double longest_move(const Points& a, const Points& b) {
  double m = 0;
  for (size_t v = 0; v < a.size(); ++v) m = std::max(m, (a[v] - b[v]).cwiseAbs().maxCoeff());
  return m;
}

// The guard's decision on a move from S to C (one stage: no longer than kStageMove) against brute
// force: with no new contact at C it holds nothing and leaves C as it is; with one it holds some
// vertex back, each one no further from S than C is (slid along the faces it met, or taken back towards
// S), and leaves no new contact. Returns whether C had a new contact. rest: the positions the guard's hierarchy is built on.
bool guard_agrees(const Mesh& rest, const Points& S, const Points& C, const std::string& what) {
  SCOPED_TRACE(what);
  EXPECT_LE(longest_move(S, C), gauss::kStageMove) << "a staged move is not what this compares";
  const gauss::MeshTopology topo = topology_of(rest);
  const Start start(topo.faces, S);
  const std::vector<uint64_t> expected = start.new_contacts(C);
  gauss::SelfIntersectionGuard guard(topo, rest.X);
  guard.start_from(S);
  Points X = C;
  const int held = guard.limit(S, X);
  if (expected.empty()) {
    EXPECT_EQ(held, 0) << "held back a move brute force finds no new contact in";
    EXPECT_TRUE(X == C);
    return false;
  }
  EXPECT_GT(held, 0) << "missed " << expected.size() << " new contacts, the first faces " << (expected[0] >> 32)
                     << " and " << (expected[0] & 0xffffffffu);
  const std::vector<uint64_t> left = start.new_contacts(X);
  EXPECT_TRUE(left.empty()) << left.size() << " new contacts left, the first faces " << (left.empty() ? 0 : left[0] >> 32)
                            << " and " << (left.empty() ? 0 : left[0] & 0xffffffffu);
  int moved = 0;
  for (size_t v = 0; v < X.size(); ++v) {
    if (X[v] == C[v]) continue;
    ++moved;
    // Held: slid (its step without the part towards the faces it met), then shortened towards S:
    // never further from S than its step went, and never further out than the step itself.
    EXPECT_LE((X[v] - S[v]).norm(), (C[v] - S[v]).norm() * (1 + 1e-12)) << "vertex " << v;
  }
  EXPECT_LE(moved, held);  // a held vertex whose step was 0 does not move
  return true;
}

// Each vertex moved by up to `amount` along each axis (uniform), seeded.
Points jittered(const Points& X, double amount, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  Points out = X;
  for (Vector3d& p : out) {
    // One draw a statement: the order in which a call's arguments are evaluated is the compiler's
    // (GCC and Clang differ), and the meshes must not depend on it.
    const double x = u(rng), y = u(rng), z = u(rng);
    p += Vector3d(x, y, z);
  }
  return out;
}

// An n by n grid of squares (two triangles each) in the plane z = 0, `size` wide, centred at 0.
Mesh sheet(int n, double size) {
  Mesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.X.emplace_back(size * (double(i) / n - 0.5), size * (double(j) / n - 0.5), 0.0);
  const auto at = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

// Two 4 by 4 sheets 0.03 wide, the second `gap` above the first with its vertices at the same x, y
// (each its own index) and its faces turned the other way (facing the first, as a scan's overlapping
// sheets do); returns the mesh and the second sheet's first vertex.
std::pair<Mesh, int> stacked_sheets(double gap) {
  Mesh m = sheet(4, 0.03);
  const int offset = static_cast<int>(m.X.size());
  const int faces = static_cast<int>(m.faces.size());
  m.X.insert(m.X.end(), m.X.begin(), m.X.end());
  for (int v = offset; v < static_cast<int>(m.X.size()); ++v) m.X[v].z() += gap;
  for (int f = 0; f < faces; ++f) m.faces.push_back({m.faces[f][0] + offset, m.faces[f][2] + offset, m.faces[f][1] + offset});
  return {m, offset};
}

// A fan of n faces around vertex 0 at the origin, its rim vertices 1..n at radius r in the plane z = 0;
// closed: the last face joins the last rim vertex to the first.
Mesh fan(int n, double r, bool closed) {
  Mesh m;
  m.X.emplace_back(0, 0, 0);
  const int rim = closed ? n : n + 1;
  const double span = closed ? 2 * M_PI : M_PI;
  for (int k = 0; k < rim; ++k) m.X.emplace_back(r * std::cos(span * k / n), r * std::sin(span * k / n), 0.0);
  for (int k = 0; k < n; ++k) m.faces.push_back({0, 1 + k, 1 + (k + 1) % rim});
  return m;
}

// The rim of a closed fan wound twice around its centre, its heights rising over the first turn and
// falling over the second: every face still faces up (a flat normal cone), but the two turns pass
// through each other halfway, in faces that share only the centre.
Points wound_twice(const Mesh& fan_mesh, double r, double rise) {
  Points X = fan_mesh.X;
  const int n = static_cast<int>(X.size()) - 1;
  for (int k = 0; k < n; ++k) {
    const double turn = 4 * M_PI * k / n, h = k < n / 2 ? double(k) / (n / 2) : double(n - k) / (n / 2);
    X[1 + k] = Vector3d(r * std::cos(turn), r * std::sin(turn), rise * h);
  }
  return X;
}

}  // namespace

// --- The flat star: pairs around a corner whose star covers no point twice are not tested. ---

TEST(SelfIntersectionShortcuts, FlatStarsOfRandomFansAsBruteForce) {
  // Closed and open fans of 5 to 12 faces, their rims moved at random (up, down, across the centre):
  // many fold, some pass through themselves, many do neither.
  int with_contact = 0, without = 0;
  for (unsigned seed = 0; seed < 240; ++seed) {
    std::mt19937 rng(seed);
    const int n = 5 + seed % 8;
    const bool closed = seed % 2 == 0;
    const Mesh m = fan(n, 0.01, closed);
    Points C = m.X;
    std::uniform_real_distribution<double> u(-1, 1);
    const double amount = seed % 3 == 0 ? 0.012 : 0.006;
    for (size_t v = 1; v < C.size(); ++v) C[v] += Vector3d(amount * u(rng), amount * u(rng), 0.5 * amount * u(rng));
    if (guard_agrees(m, m.X, C, "fan seed " + std::to_string(seed))) ++with_contact;
    else ++without;
  }
  // Both decisions were put to the test.
  EXPECT_GT(with_contact, 20);
  EXPECT_GT(without, 20);
}

TEST(SelfIntersectionShortcuts, AFanWoundTwiceAroundItsCentreIsCaught) {
  // Every face faces up, but the star covers its centre's surroundings twice and its two turns cross:
  // neither the star nor a patch of such faces is flat.
  for (int n : {8, 12, 16}) {
    const Mesh m = fan(n, 0.01, true);
    const Points C = wound_twice(m, 0.01, 0.004);
    EXPECT_TRUE(guard_agrees(m, m.X, C, "wound twice, " + std::to_string(n) + " faces"));
  }
  // The same on a sheet: the centre of a 6 by 6 grid's star wound twice, the rest left flat.
  Mesh s = sheet(6, 0.04);
  const int centre = 3 * 7 + 3;
  std::vector<int> ring;  // the centre's neighbours, in turn around it
  for (const Vector3d& d : {Vector3d(1, 0, 0), Vector3d(1, 1, 0), Vector3d(0, 1, 0), Vector3d(-1, 0, 0),
                            Vector3d(-1, -1, 0), Vector3d(0, -1, 0)})
    for (int v = 0; v < static_cast<int>(s.X.size()); ++v)
      if ((s.X[v] - s.X[centre] - d * (0.04 / 6)).norm() < 1e-9) ring.push_back(v);
  ASSERT_EQ(ring.size(), 6u);
  Points C = s.X;
  for (int k = 0; k < 6; ++k) {  // the six neighbours spread over two turns, rising then falling
    const double turn = 4 * M_PI * k / 6 + 0.1, h = k < 3 ? k / 3.0 : (6 - k) / 3.0;
    C[ring[k]] = s.X[centre] + Vector3d(0.006 * std::cos(turn), 0.006 * std::sin(turn), 0.003 * h);
  }
  guard_agrees(s, s.X, C, "a sheet's star wound twice");
}

TEST(SelfIntersectionShortcuts, TwoSheetsSharingOneVertexAsBruteForce) {
  // Two open fans that meet only in their centre (a non-manifold vertex): each is flat, but together
  // their wedges can overlap, and one tilted through the other crosses it in faces sharing the centre.
  for (unsigned seed = 0; seed < 60; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    Mesh m;
    m.X.emplace_back(0, 0, 0);
    const int n = 3;
    // first sheet: a half disc on y >= 0; second: a half disc on y <= 0, sharing vertex 0.
    for (int sheet_index = 0; sheet_index < 2; ++sheet_index) {
      const int base = static_cast<int>(m.X.size());
      for (int k = 0; k <= n; ++k) {
        const double a = M_PI * k / n + sheet_index * M_PI;
        m.X.emplace_back(0.01 * std::cos(a), 0.01 * std::sin(a), 0.0);
      }
      for (int k = 0; k < n; ++k) m.faces.push_back({0, base + k, base + k + 1});
    }
    // The second sheet tilted about its own middle line (the -y axis) by up to 60 degrees, then spun
    // about z by up to half a turn: onto the first sheet's side, through it, or clear of it.
    const double tilt = (u(rng) * 2 - 1) * 60 * M_PI / 180, spin = u(rng) * M_PI;
    const Eigen::Matrix3d turn = (Eigen::AngleAxisd(spin, Vector3d::UnitZ()) * Eigen::AngleAxisd(tilt, Vector3d::UnitY())).toRotationMatrix();
    Points C = m.X;
    for (size_t v = n + 2; v < C.size(); ++v) C[v] = turn * m.X[v];
    // The last stage of the way there, as a run would get there, from a state without contacts.
    const double stages = std::ceil(longest_move(m.X, C) / gauss::kStageMove);
    Points mid = m.X;
    for (size_t v = 0; v < C.size(); ++v) mid[v] = m.X[v] + (C[v] - m.X[v]) * ((stages - 1) / stages);
    if (!contacts(m.faces, mid).empty()) continue;
    guard_agrees(m, mid, C, "two sheets, seed " + std::to_string(seed));
  }
}

// --- Pairs that share corners: an edge never counts, a corner only by crossing. ---

TEST(SelfIntersectionShortcuts, SharedCornersOfRandomFoldedSheetsAsBruteForce) {
  // A 5 by 5 sheet folded along a random line by up to 180 degrees (onto itself, through itself) and
  // jittered: neighbours fold onto each other across shared edges and corners, and far faces meet.
  int with_contact = 0, without = 0;
  for (unsigned seed = 0; seed < 360; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    const Mesh m = sheet(5, 0.03);
    const double angle = std::abs(u(rng)) * M_PI * 1.02, direction = u(rng) * M_PI, offset = 0.01 * u(rng);
    const Vector3d axis(std::cos(direction), std::sin(direction), 0), normal(-axis.y(), axis.x(), 0);
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    Points C = m.X;
    for (Vector3d& p : C) {
      const double side = p.dot(normal) - offset;
      if (side > 0) p = offset * normal + turn * (p - offset * normal);
    }
    C = jittered(C, 0.0015, seed + 1000);
    // From a state part of the way there (the run's previous step), clean by brute force.
    Points S = m.X;
    for (size_t v = 0; v < C.size(); ++v) S[v] = m.X[v] + 0.6 * (C[v] - m.X[v]);
    if (!contacts(m.faces, S).empty() || longest_move(S, C) > gauss::kStageMove) continue;
    if (guard_agrees(m, S, C, "folded sheet, seed " + std::to_string(seed))) ++with_contact;
    else ++without;
  }
  EXPECT_GT(with_contact, 10);
  EXPECT_GT(without, 10);
}

TEST(SelfIntersectionShortcuts, NearlyCoplanarNeighboursAndSliversAsBruteForce) {
  // A sheet lifted out of its plane by rounding-sized amounts (nothing to hold), and one whose
  // vertices slide onto their neighbours' edges (slivers, zero-area faces) and past them.
  const Mesh m = sheet(6, 0.03);
  for (double amount : {1e-15, 1e-12, 1e-9}) {
    Points C = m.X;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-amount, amount);
    for (Vector3d& p : C) p.z() += u(rng);
    EXPECT_FALSE(guard_agrees(m, m.X, C, "lifted by " + std::to_string(amount)));
  }
  // A dent whose tail lifts faces by 1e-15 and less: next to each other, sharing a corner with edges
  // in line through it, they are one plane to rounding, not a crossing (triangles_cross took them for
  // one before it treated planes within 1e-9 radians as one).
  const Mesh fine = sheet(32, 0.05);
  for (const Vector3d& centre : {Vector3d(-0.00413, -0.0164, 0), Vector3d(0.0071, 0.0033, 0)}) {
    Points C = fine.X;
    for (Vector3d& p : C) p.z() -= 0.004 * std::exp(-(p - centre).head<2>().squaredNorm() / (0.003 * 0.003));
    EXPECT_EQ(gauss::count_self_intersections(fine.faces, C), 0);
    EXPECT_FALSE(guard_agrees(fine, fine.X, C, "a dent's tail"));
  }
  int with_contact = 0;
  for (unsigned seed = 0; seed < 80; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    Points C = m.X;
    const double h = 0.03 / 6;
    for (int v = 0; v < static_cast<int>(C.size()); ++v) {
      if (u(rng) < 0.5) continue;
      // along x by up to 1.3 cells (onto and past the next vertex), a little up or down
      C[v] += Vector3d(1.3 * h * u(rng), 0, (u(rng) - 0.5) * (seed % 2 ? 1e-3 : 1e-9) * h);
    }
    with_contact += guard_agrees(m, m.X, C, "slivers, seed " + std::to_string(seed));
  }
  EXPECT_GT(with_contact, 5);
}

TEST(SelfIntersectionShortcuts, DuplicatedVerticesTouchAtTheStartAndMayNotCross) {
  // Two sheets stacked on each other, their vertices at the same places (each its own index): every
  // pair of faces touches at the start, which is allowed; pushed through each other, they may not cross.
  const auto [m, offset] = stacked_sheets(0.0);
  ASSERT_GT(contacts(m.faces, m.X).size(), 0u);
  ASSERT_EQ(Start(m.faces, m.X).crossing.size(), 0u);
  for (unsigned seed = 0; seed < 30; ++seed) {
    const Points C = jittered(m.X, 0.002, seed);
    EXPECT_TRUE(guard_agrees(m, m.X, C, "stacked, seed " + std::to_string(seed)));
  }
  // Lifted apart evenly: no crossing, nothing held.
  Points C = m.X;
  for (int v = offset; v < static_cast<int>(C.size()); ++v) C[v].z() += 0.001;
  EXPECT_FALSE(guard_agrees(m, m.X, C, "lifted apart"));
}

TEST(SelfIntersectionShortcuts, SheetsAHairApartAtTheStartMayTouchButNotCross) {
  // Two sheets stacked a gap apart (a scan's overlapping sheets): between the contact margin and the
  // start's margin they count as touching from the start, so pressing them closer holds nothing
  // back; pressing them through each other is held. Farther apart at the start, pressing them a hair
  // apart holds nothing (the start's margin is not the steps'), within the contact margin is a new
  // contact and is held.
  // The upper sheet moved down by `by`, or only its half at x < 0 (bent through the lower sheet).
  const auto pressed = [](const Mesh& m, int offset, double by, bool half = false) {
    Points C = m.X;
    for (int v = offset; v < static_cast<int>(C.size()); ++v)
      if (!half || C[v].x() < 0) C[v].z() -= by;
    return C;
  };
  const double hair = 0.5 * (gauss::kContactMargin + gauss::kStartMargin);
  const auto [near, near_offset] = stacked_sheets(hair);
  EXPECT_FALSE(guard_agrees(near, near.X, pressed(near, near_offset, 0.9 * hair), "a hair apart, pressed closer"));
  EXPECT_TRUE(guard_agrees(near, near.X, pressed(near, near_offset, hair + 0.003, true), "a hair apart, bent through"));
  const auto [far, far_offset] = stacked_sheets(2 * gauss::kStartMargin);
  EXPECT_FALSE(guard_agrees(far, far.X, pressed(far, far_offset, 2 * gauss::kStartMargin - hair),
                            "farther apart, pressed to a hair apart (the start's margin is the start's alone)"));
  EXPECT_TRUE(guard_agrees(far, far.X, pressed(far, far_offset, 2 * gauss::kStartMargin - 0.5 * gauss::kContactMargin),
                           "farther apart, pressed within the margin"));
}

// --- Flat patches: the pairs inside a node of the hierarchy whose faces all face one way. ---

TEST(SelfIntersectionShortcuts, FlatPatchesOfJitteredIcospheresAsBruteForce) {
  // Icospheres (80 and 320 faces, radius 0.02) jittered by up to half an edge and more: patches whose
  // normals stay within the cone, and some that fold.
  int with_contact = 0, without = 0;
  for (unsigned seed = 0; seed < 120; ++seed) {
    Mesh m = mesh_of(gauss_test::icosphere(seed % 3 == 0 ? 2 : 1));
    scale_to(m.X, 0.04);
    const double amount = (seed % 4 + 1) * 0.002;
    const Points C = jittered(m.X, amount, seed);
    if (guard_agrees(m, m.X, C, "icosphere, seed " + std::to_string(seed))) ++with_contact;
    else ++without;
  }
  EXPECT_GT(with_contact, 10);
  EXPECT_GT(without, 10);
}

TEST(SelfIntersectionShortcuts, FlatPatchesOfASheetPressedOntoAnotherAsBruteForce) {
  // A fine sheet (1152 faces) 0.004 above a second one: the hierarchy's nodes hold faces of both,
  // facing the same way, but not connected, so not a flat patch. A narrow bump pressed down at random
  // places stays clear of the lower sheet, just touches it or passes through it in a few faces, inside one node or
  // across nodes.
  Mesh m = sheet(24, 0.05);
  const int offset = static_cast<int>(m.X.size());
  const int faces = static_cast<int>(m.faces.size());
  for (int v = 0; v < offset; ++v) m.X.push_back(m.X[v] - Vector3d(0, 0, 0.004));
  for (int f = 0; f < faces; ++f) m.faces.push_back({m.faces[f][0] + offset, m.faces[f][1] + offset, m.faces[f][2] + offset});
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  for (int press = 0; press < 6; ++press) {
    const double x = u(rng), y = u(rng);
    for (double depth : {0.0035, 0.0042, 0.006}) {
      Points C = m.X;
      for (int v = 0; v < offset; ++v) {
        const double r2 = (C[v].head<2>() - Eigen::Vector2d(x, y)).squaredNorm() / (0.006 * 0.006);
        if (r2 < 1) C[v].z() -= depth * (1 - r2) * (1 - r2);
      }
      const bool contact = guard_agrees(m, m.X, C, "pressed " + std::to_string(depth) + " at " + std::to_string(press));
      if (depth != 0.0042) {  // 0.0042 reaches the sheet below or not
        EXPECT_EQ(contact, depth > 0.004);
      }
    }
  }
}

TEST(SelfIntersectionShortcuts, SharedMeshesJitteredAsBruteForce) {
  // Meshes of ../shared/meshes (with boundary, broken), scaled to the solver's frame, moved at random by
  // up to three-quarters of a stage.
  const std::vector<std::string> names = {"boundary/cat_head_131.obj", "boundary/cube_no_bottom_25.obj",
                                          "bad/fan3_nonmanifold_edge.obj", "bad/degtri_sliding_zero_area.obj",
                                          "boundary/hand_lowres_810.obj"};
  if (!std::ifstream(gauss_test::shared_mesh(names[0])).good()) GTEST_SKIP() << "../shared/meshes not present";
  for (const std::string& name : names) {
    Mesh m = mesh_of(gauss::read_mesh(gauss_test::shared_mesh(name)));
    scale_to(m.X, 1.0);
    const int seeds = m.faces.size() > 1000 ? 4 : 12;
    for (int seed = 0; seed < seeds; ++seed) {
      const Points C = jittered(m.X, 0.015, seed);
      guard_agrees(m, m.X, C, name + ", seed " + std::to_string(seed));
    }
  }
}

// --- What took the place of the fallback that returned every vertex. ---

TEST(SelfIntersectionShortcuts, AContactAlreadyAtSafeHoldsOnlyItsCornersAndEnds) {
  // The guard takes no vertex back wholesale: only the corners of faces in a new
  // contact step back, down to `safe`, and a contact `safe` itself has (a start the guard was not told
  // of) ends the loop there. Two sheets of which the second is moved into the first, the guard started
  // from them apart: told to limit a move from the crossing state, it ends with every new contact
  // left having all six corners at `safe`, and the mesh away from the crossing takes its step.
  Mesh m = sheet(8, 0.04);
  const int offset = static_cast<int>(m.X.size());
  const int faces = static_cast<int>(m.faces.size());
  for (int v = 0; v < offset; ++v) m.X.push_back(Eigen::AngleAxisd(0.3, Vector3d::UnitX()) * m.X[v] + Vector3d(0.0011, 0.0007, 0.01));
  for (int f = 0; f < faces; ++f) m.faces.push_back({m.faces[f][0] + offset, m.faces[f][1] + offset, m.faces[f][2] + offset});
  ASSERT_TRUE(contacts(m.faces, m.X).empty());
  Points safe = m.X;
  for (int v = offset; v < static_cast<int>(safe.size()); ++v) safe[v].z() -= 0.01;  // through the first sheet
  ASSERT_GT(contacts(m.faces, safe).size(), 0u);
  const gauss::MeshTopology topo = topology_of(m);
  gauss::SelfIntersectionGuard guard(topo, m.X);
  guard.start_from(m.X);
  const Points C = jittered(safe, 0.001, 3);
  Points X = C;
  const int held = guard.limit(safe, X);
  const std::vector<uint64_t> left = Start(m.faces, m.X).new_contacts(X);
  EXPECT_GT(left.size(), 0u) << "the crossing at safe stays";
  for (uint64_t k : left)
    for (int f : {static_cast<int>(k >> 32), static_cast<int>(k & 0xffffffffu)})
      for (int v : m.faces[f]) EXPECT_EQ(X[v], safe[v]) << "a corner of faces " << (k >> 32) << ", " << (k & 0xffffffffu);
  EXPECT_GT(held, 0);
  EXPECT_LT(held, static_cast<int>(X.size()) / 2) << "held back far more than the contact";
  for (size_t v = 0; v < X.size(); ++v)  // three cells (0.005 each) from the line where they cross
    if (std::abs(safe[v].y()) > 0.015) {
      EXPECT_EQ(X[v], C[v]) << v;
    }
}

TEST(SelfIntersectionShortcuts, ASheetPressedOntoAnotherSlidesAlongIt) {
  // A small sheet 0.005 above a larger one is moved sideways by 0.01 and down onto it (to within the
  // contact margin). The guard takes off only the part of each held step that goes towards the other
  // sheet: the small sheet slides the whole 0.01 and stays 0.005 above (halving its step instead kept
  // a quarter or half of the sideways move, and a run pressed against itself stopped styling there).
  Mesh m = sheet(8, 0.08);
  const int offset = static_cast<int>(m.X.size());
  const Mesh top = sheet(4, 0.03);
  for (const Vector3d& p : top.X) m.X.push_back(p + Vector3d(0.0013, 0.0007, 0.005));
  for (const auto& f : top.faces) m.faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
  ASSERT_TRUE(contacts(m.faces, m.X).empty());
  Points C = m.X;
  for (int v = offset; v < static_cast<int>(C.size()); ++v) C[v] += Vector3d(0.01, 0.0, -0.00502);
  ASSERT_GT(contacts(m.faces, C).size(), 0u) << "the move ends within the contact margin";
  const gauss::MeshTopology topo = topology_of(m);
  gauss::SelfIntersectionGuard guard(topo, m.X);
  guard.start_from(m.X);
  Points X = C;
  EXPECT_GT(guard.limit(m.X, X), 0);
  EXPECT_TRUE(Start(m.faces, m.X).new_contacts(X).empty());
  for (int v = offset; v < static_cast<int>(X.size()); ++v)
    EXPECT_LT((X[v] - (m.X[v] + Vector3d(0.01, 0.0, 0.0))).norm(), 1e-12) << v;
  for (int v = 0; v < offset; ++v) EXPECT_EQ(X[v], m.X[v]) << v;
}

// --- Threads. ---

TEST(SelfIntersectionShortcuts, OneAndTwoThreadsAreBitIdentical) {
  // Two icospheres of 5120 faces each (above the sizes where the pair search and the flat stars go
  // parallel) moved into each other: the held vertices and where they end are the same bit for bit.
  gauss::TriangleMesh a = gauss_test::icosphere(4);
  const int64_t offset = a.num_vertices();
  const std::vector<double> b = a.V;
  for (size_t i = 0; i < b.size(); ++i) a.V.push_back(b[i] + (i % 3 == 0 ? 2.01 : 0.0));  // 0.01 apart
  for (int64_t i = 0, n = static_cast<int64_t>(a.F.size()); i < n; ++i) a.F.push_back(a.F[i] + offset);
  Mesh m = mesh_of(a);
  scale_to(m.X, 1.0);
  // moved 0.015 towards each other and jittered: they overlap by about half of that
  Points C = jittered(m.X, 0.002, 11);
  for (int v = static_cast<int>(offset); v < static_cast<int>(C.size()); ++v) C[v].x() -= 0.015;
  const gauss::MeshTopology topo = topology_of(m);
  const int saved = gauss::parallel::max_threads();
  gauss::parallel::set_max_threads(2);
  std::vector<Points> result;
  std::vector<int> held;
  for (int threads : {1, 2}) {
    const gauss::parallel::ScopedThreads scoped(threads);
    gauss::SelfIntersectionGuard guard(topo, m.X);
    guard.start_from(m.X);
    Points X = C;
    held.push_back(guard.limit(m.X, X));
    result.push_back(X);
  }
  gauss::parallel::set_max_threads(saved);
  EXPECT_GT(held[0], 0);
  EXPECT_EQ(held[0], held[1]);
  for (size_t v = 0; v < C.size(); ++v) ASSERT_TRUE(result[0][v] == result[1][v]) << v;
}

}  // namespace test_self_intersection_shortcuts
