#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "gauss/style/preference_function.h"
#include "gauss/style/presets.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_preference_function {

using gauss::PreferenceFunction;
using gauss::preset_names;
using gauss::preset_style;
using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

// Fixed directions and no rings (the developable sheet_metal has neither).
bool is_discrete(const std::string& name) {
  const gauss::StyleParams p = preset_style(name);
  return p.ring_offsets.empty() && p.kind == gauss::StyleKind::directions;
}

Vector3d some_unit(int i) {
  return Vector3d(std::sin(1.3 * i + 0.2), std::cos(0.7 * i + 1.1), std::sin(2.1 * i + 0.5)).normalized();
}

}  // namespace

TEST(PreferenceFunction, EqualsOneAtEveryPreferredNormalOfEveryDiscretePreset) {
  for (const std::string& name : preset_names()) {
    if (!is_discrete(name)) continue;
    for (double sigma : {1.0, 4.0, 10.0, 100.0}) {
      gauss::StyleParams p = preset_style(name);
      p.sigma = sigma;
      PreferenceFunction g(p);
      ASSERT_FALSE(g.normals().empty()) << name;
      for (const Vector3d& n : g.normals()) EXPECT_NEAR(g.value(n), 1.0, 1e-9) << name << " sigma " << sigma;
    }
  }
}

TEST(PreferenceFunction, RingsEqualOneOnTheirCircle) {
  for (const char* name : {"cylinder", "cone", "double_cone"}) {
    gauss::StyleParams p = preset_style(name);
    p.axis_contribution = 0.0;  // isolate the circle terms
    PreferenceFunction g(p);
    for (double d : g.ring_offsets())
      for (int k = 0; k < 8; ++k) {
        const double a = 0.7 * k, r = std::sqrt(1 - d * d);
        EXPECT_NEAR(g.value(Vector3d(r * std::cos(a), r * std::sin(a), d)), 1.0, 1e-9) << name;
      }
  }
}

TEST(PreferenceFunction, PresetsHaveTheRightNumberOfNormals) {
  EXPECT_EQ(preset_style("cube").normals.size(), 6u);
  EXPECT_EQ(preset_style("tetrahedron").normals.size(), 4u);
  EXPECT_EQ(preset_style("octahedron").normals.size(), 8u);
  EXPECT_EQ(preset_style("dodecahedron").normals.size(), 12u);
  EXPECT_EQ(preset_style("icosahedron").normals.size(), 20u);
  EXPECT_EQ(preset_style("square_pyramid").normals.size(), 5u);
  EXPECT_EQ(preset_style("truncated_pyramid").normals.size(), 6u);
  EXPECT_EQ(preset_style("triangular_prism").normals.size(), 5u);
  EXPECT_EQ(preset_style("hexagonal_prism").normals.size(), 8u);
  EXPECT_EQ(preset_style("double_cone").ring_offsets.size(), 2u);
  // Regular solids: all face normals at the same angle to their nearest neighbour.
  for (const char* name : {"tetrahedron", "octahedron", "dodecahedron", "icosahedron"}) {
    const auto n = PreferenceFunction(preset_style(name)).normals();
    double nearest_first = -2;
    for (size_t i = 0; i < n.size(); ++i) {
      double best = -2;
      for (size_t j = 0; j < n.size(); ++j)
        if (i != j) best = std::max(best, n[i].dot(n[j]));
      if (i == 0) nearest_first = best;
      EXPECT_NEAR(best, nearest_first, 1e-12) << name;
    }
  }
  EXPECT_THROW(preset_style("sphere"), std::invalid_argument);
}

TEST(PreferenceFunction, GradientAndHessianMatchFiniteDifferences) {
  for (const std::string& name : preset_names()) {
    for (double sigma : {2.0, 4.0, 20.0}) {
      gauss::StyleParams p = preset_style(name);
      p.sigma = sigma;
      p.rotation = Eigen::AngleAxisd(0.3, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
      PreferenceFunction g(p);
      for (int i = 0; i < 10; ++i) {
        const Vector3d x = some_unit(i);
        double v;
        Vector3d grad;
        Matrix3d hess;
        g.evaluate(x, v, grad, hess);
        EXPECT_NEAR(v, g.value(x), 1e-14);
        const double h = 1e-6;
        for (int k = 0; k < 3; ++k) {
          Vector3d xp = x, xm = x;
          xp[k] += h;
          xm[k] -= h;
          const double fd = (g.value(xp) - g.value(xm)) / (2 * h);
          EXPECT_NEAR(grad[k], fd, 1e-6 * (1 + std::abs(fd))) << name << " sigma " << sigma;
          double vp, vm;
          Vector3d gp, gm;
          Matrix3d hp, hm;
          g.evaluate(xp, vp, gp, hp);
          g.evaluate(xm, vm, gm, hm);
          const Vector3d hcol = (gp - gm) / (2 * h);
          for (int r = 0; r < 3; ++r)
            EXPECT_NEAR(hess(r, k), hcol[r], 1e-5 * (1 + std::abs(hcol[r]))) << name << " sigma " << sigma;
        }
      }
    }
  }
}

TEST(PreferenceFunction, StaysFiniteForLargeSigma) {
  for (const std::string& name : preset_names())
    for (double sigma : {100.0, 500.0}) {
      gauss::StyleParams p = preset_style(name);
      p.sigma = sigma;
      PreferenceFunction g(p);
      for (int i = 0; i < 50; ++i) {
        double v;
        Vector3d grad;
        Matrix3d hess;
        g.evaluate(some_unit(i), v, grad, hess);
        EXPECT_TRUE(std::isfinite(v) && grad.allFinite() && hess.allFinite()) << name << " sigma " << sigma;
      }
      if (is_discrete(name))
        for (const Vector3d& n : g.normals()) EXPECT_NEAR(g.value(n), 1.0, 1e-9) << name;
    }
}

TEST(PreferenceFunction, RotationRotatesTheFunction) {
  gauss::StyleParams p = preset_style("tetrahedron");
  PreferenceFunction plain(p);
  p.rotation = Eigen::AngleAxisd(1.1, Vector3d(0.2, -1, 0.4).normalized()).toRotationMatrix();
  PreferenceFunction turned(p);
  for (int i = 0; i < 20; ++i) {
    const Vector3d x = some_unit(i);
    EXPECT_NEAR(turned.value(p.rotation * x), plain.value(x), 1e-12);
  }
}

TEST(PreferenceFunction, DuplicateNormalsStillNormalize) {
  gauss::StyleParams p;
  p.normals = {Vector3d(0, 0, 1), Vector3d(0, 0, 1), Vector3d(1, 0, 0)};
  PreferenceFunction g(p);
  EXPECT_NEAR(g.value(Vector3d(0, 0, 1)), 1.0, 1e-9);
  EXPECT_NEAR(g.value(Vector3d(1, 0, 0)), 1.0, 1e-9);
}

TEST(PreferenceFunction, RejectsNonsense) {
  gauss::StyleParams p = preset_style("cube");
  auto expect_error = [](gauss::StyleParams q, const char* needle) {
    try {
      PreferenceFunction g(q);
      ADD_FAILURE() << "no error for " << needle;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  auto q = p; q.sigma = 0; expect_error(q, "sigma");
  q = p; q.sigma = -1; expect_error(q, "sigma");
  q = p; q.sigma = NAN; expect_error(q, "sigma");
  q = p; q.mu = -1; expect_error(q, "mu");
  q = p; q.normals.clear(); expect_error(q, "at least one");
  q = p; q.normals[0] = Vector3d::Zero(); expect_error(q, "non-zero");
  q = p; q.normals[0] = Vector3d(NAN, 0, 0); expect_error(q, "finite");
  q = p; q.rotation = Matrix3d::Identity() * 2; expect_error(q, "rotation");
  q = p; q.rotation = -Matrix3d::Identity(); expect_error(q, "rotation");
  q = preset_style("cone"); q.ring_offsets = {1.5}; expect_error(q, "ring offsets");
  q = preset_style("cone"); q.axis = Vector3d::Zero(); expect_error(q, "axis");
}

}  // namespace test_preference_function
