#pragma once
// Assertions the C++ tests share.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace gauss_test {

// f() must throw std::invalid_argument whose message contains `words` (bad input is refused with a
// message that says what is wrong).
template <typename F>
void expect_refused(F&& f, const std::string& words) {
  try {
    f();
    ADD_FAILURE() << "accepted; expected std::invalid_argument mentioning '" << words << "'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << "message: " << e.what();
  }
}

}  // namespace gauss_test
