// Error codes: every code has its own stable snake_case name, and the one-argument constructor means an
// argument check.
#include "core/error.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "test_support.h"

namespace sd {
namespace {

TEST(ErrorCodes, DistinctSnakeCaseNames) {
  std::set<std::string> names;
  for (ErrorCode code : all_error_codes()) {
    const std::string name = error_code_name(code);
    EXPECT_TRUE(test::is_snake_case(name)) << name;
    EXPECT_TRUE(names.insert(name).second) << "twice: " << name;
  }
  EXPECT_EQ(names.size(), static_cast<size_t>(ErrorCode::Internal) + 1) << "a code is missing from all_error_codes()";
}

TEST(ErrorCodes, OneArgumentErrorsAreArgumentErrors) {
  const Error plain("handles: group 0 is empty");
  EXPECT_EQ(plain.code(), ErrorCode::InvalidArgument);
  EXPECT_STREQ(plain.what(), "handles: group 0 is empty");
  const Error coded(ErrorCode::Cancelled, "binding cancelled");
  EXPECT_EQ(coded.code(), ErrorCode::Cancelled);
  EXPECT_STREQ(error_code_name(coded.code()), "cancelled");
}

}  // namespace
}  // namespace sd
