// The external readers the tests run (tests/support/readers.h): all installed, and the rule for a
// missing one (fail; skip only with AGGPACK_REQUIRE_READERS=0).
#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>

#include "support/readers.h"

namespace aggpack {
namespace {

// Sets an environment variable for one test and puts the old value back.
class ScopedEnvironment {
 public:
  ScopedEnvironment(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value == nullptr) {
      ::unsetenv(name);
    } else {
      ::setenv(name, value, 1);
    }
  }
  ~ScopedEnvironment() {
    if (old_) {
      ::setenv(name_, old_->c_str(), 1);
    } else {
      ::unsetenv(name_);
    }
  }
  ScopedEnvironment(const ScopedEnvironment&) = delete;
  ScopedEnvironment& operator=(const ScopedEnvironment&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// One line per missing reader, so that CI names all of them at once.
TEST(ExternalReaders, EveryReaderTheTestsUseIsInstalled) {
  std::string missing;
  for (const auto& reader : test::kExternalReaders) {
    if (!test::is_reader_installed(reader)) {
      missing += "\n  " + test::missing_reader_message(reader.name);
    }
  }
  if (missing.empty()) return;
  if (!test::are_readers_required()) GTEST_SKIP() << "AGGPACK_REQUIRE_READERS=0:" << missing;
  FAIL() << "missing external readers:" << missing;
}

TEST(ExternalReaders, MissingReadersFailUnlessTheVariableIsZero) {
  {
    const ScopedEnvironment unset("AGGPACK_REQUIRE_READERS", nullptr);
    EXPECT_TRUE(test::are_readers_required());
  }
  {
    const ScopedEnvironment ci("AGGPACK_REQUIRE_READERS", "1");
    EXPECT_TRUE(test::are_readers_required());
  }
  {
    const ScopedEnvironment developer("AGGPACK_REQUIRE_READERS", "0");
    EXPECT_FALSE(test::are_readers_required());
  }
}

TEST(ExternalReaders, AnAbsentProgramIsReportedWithItsPackage) {
  const test::ExternalReader absent{
      .name = "aggpack-no-such-reader", .is_python_module = false, .debian_package = "none"};
  EXPECT_FALSE(test::is_reader_installed(absent));
  const test::ExternalReader absent_module{
      .name = "aggpack_no_such_module", .is_python_module = true, .debian_package = "none"};
  EXPECT_FALSE(test::is_reader_installed(absent_module));
  EXPECT_NE(test::missing_reader_message("no-such-name").find("unknown external reader"),
            std::string::npos);
}

}  // namespace
}  // namespace aggpack
