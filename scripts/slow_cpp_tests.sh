# Sourced by the test scripts: the slow C++ cases of tests/cpp/slow_tests.txt as
#   SLOW_CPP_TESTS_REGEX   for ctest -E
#   SLOW_CPP_TESTS_FILTER  for a gtest binary's --gtest_filter (a negative filter)
_slow_patterns="$(grep -v '^\s*\(#\|$\)' "$(dirname "${BASH_SOURCE[0]}")/../tests/cpp/slow_tests.txt")"
SLOW_CPP_TESTS_REGEX="$(sed 's/\./\\./g; s/\*/.*/g' <<< "$_slow_patterns" | paste -sd'|')"
SLOW_CPP_TESTS_FILTER="-$(paste -sd':' <<< "$_slow_patterns")"
unset _slow_patterns
