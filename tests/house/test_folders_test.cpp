// The suite leaves nothing in the temp folder: each test's folder sits directly in it, so that
// removing the folder removes all the test made.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "test_support.hpp"

namespace archet {
namespace {

// A parameterised test is named "Name/0": that slash made a folder inside a folder, and only
// the inner one was removed, leaving an empty "archet-test-…-Name" behind after every run.
TEST(TestFolders, AParameterisedTestsFolderSitsDirectlyInTheTempFolder) {
    const auto dir = test::temp_dir("house-" + std::string("TheNameOfATest/3"));
    EXPECT_EQ(dir.parent_path(), std::filesystem::temp_directory_path());
    EXPECT_TRUE(std::filesystem::is_directory(dir));
    EXPECT_NE(dir.filename().string().find("TheNameOfATest"), std::string::npos)
        << "the folder still says which test made it: " << dir;
}

}  // namespace
}  // namespace archet
