// Under CI (CI=true) a skipped C++ test fails, as a skipped Python test does (tests/common/ci_skips.py):
// on CI's machine every test has what it needs (../shared/meshes, the fuzzing corpus), and a skip there
// hides a missing file or install step. Registered at start-up for every test of gauss_tests, so ctest,
// the sanitizer run and the Windows run under wine all apply it; gtest's totals print the skip count.
#include <gtest/gtest.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_ci_skips {

namespace {

bool in_ci() {
  const char* value = std::getenv("CI");
  std::string ci = value ? value : "";
  for (char& c : ci) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ci == "true";
}

// The reasons a test gave for skipping (GTEST_SKIP's messages), joined.
std::string skip_reasons(const testing::TestResult& result) {
  std::string reasons;
  for (int i = 0; i < result.total_part_count(); ++i) {
    const testing::TestPartResult& part = result.GetTestPartResult(i);
    if (part.skipped()) reasons += (reasons.empty() ? "" : "; ") + std::string(part.message());
  }
  return reasons;
}

// Appended after gtest's printer, so the failure is reported as the test's own; a listener may raise
// failures in OnTestEnd (gtest's "Generating failures in listeners").
class SkipsFailUnderCi : public testing::EmptyTestEventListener {
  void OnTestEnd(const testing::TestInfo& info) override {
    if (in_ci() && info.result()->Skipped()) {
      ADD_FAILURE() << "skipped under CI=true, where every test must run (tests/cpp/test_ci_skips.cpp): "
                    << skip_reasons(*info.result());
    }
  }
};

const bool kRegistered = [] {
  testing::UnitTest::GetInstance()->listeners().Append(new SkipsFailUnderCi);
  return true;
}();

const char* const kChild = "GAUSS_CI_SKIPS_CHILD";

}  // namespace

// The child's output as a failure message shows it: with gtest's skip marker reworded, since ctest counts
// a test whose output has that marker as skipped, even when it failed.
std::string shown(std::string out) {
  const std::string marker = std::string("[  SKIPPED") + " ]";
  for (size_t at = out.find(marker); at != std::string::npos; at = out.find(marker, at)) out.replace(at, 3, "[ (");
  return out;
}

TEST(CiSkips, ASkipUnderCiFailsWithItsReasonAndIsASkipOtherwise) {
  // The runs below start this test again with kChild set: then it skips, giving kChild as its reason.
  if (const char* reason = std::getenv(kChild)) GTEST_SKIP() << reason;
  ASSERT_TRUE(kRegistered);
#if defined(__linux__)
  const std::string exe = std::filesystem::read_symlink("/proc/self/exe").string();
  const std::string log = testing::TempDir() + "gauss_ci_skips_child.log";
  auto run_child = [&](const char* ci, std::string& out) {
    const std::string command = std::string("CI=") + ci + " " + kChild + "='../shared/meshes not present' '" + exe +
                                "' --gtest_filter=CiSkips.ASkipUnderCiFailsWithItsReasonAndIsASkipOtherwise"
                                " --gtest_color=no > '" + log + "' 2>&1";
    const int status = std::system(command.c_str());
    std::ifstream in(log);
    std::ostringstream text;
    text << in.rdbuf();
    out = text.str();
    return status;
  };
  const std::string skipped = std::string("[  SKIPPED") + " ] CiSkips.";
  std::string out;
  EXPECT_NE(run_child("true", out), 0) << shown(out);
  EXPECT_NE(out.find("skipped under CI=true, where every test must run"), std::string::npos) << shown(out);
  EXPECT_NE(out.find("../shared/meshes not present"), std::string::npos) << shown(out);
  EXPECT_NE(out.find("[  FAILED  ] CiSkips."), std::string::npos) << shown(out);
  EXPECT_EQ(out.find(skipped), std::string::npos) << shown(out);  // ctest would call it skipped
  EXPECT_EQ(run_child("false", out), 0) << shown(out);
  EXPECT_NE(out.find(skipped), std::string::npos) << shown(out);
  EXPECT_EQ(out.find("FAILED"), std::string::npos) << shown(out);
  std::remove(log.c_str());
#endif  // elsewhere (the Windows run under wine) the listener is in place, and cross_check.sh reads the skips too
}

}  // namespace test_ci_skips
