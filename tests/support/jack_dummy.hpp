#pragma once
// A JACK server of the test's own on the dummy driver (no sound card), named after the test
// process so that parallel suites do not meet; this process and the ones it starts find it
// through JACK_DEFAULT_SERVER. Skips the test where jackd is not installed.

#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace archet::test {

class JackDummy : public ::testing::Test {
  protected:
    void SetUp() override {
        if (::access("/usr/bin/jackd", X_OK) != 0)
            GTEST_SKIP() << "jackd is not installed (Debian package jackd2)";
        name_ = "archet-test-" + std::to_string(::getpid());
        std::vector<std::string> args{"/usr/bin/jackd", "-n", name_, "-d", "dummy", "-r",
                                      "48000",          "-p", "64"};
        std::vector<char*> argv;
        for (auto& a : args) argv.push_back(a.data());
        argv.push_back(nullptr);
        ASSERT_EQ(::posix_spawn(&pid_, argv[0], nullptr, nullptr, argv.data(), environ), 0);
        ::setenv("JACK_DEFAULT_SERVER", name_.c_str(), 1);
        // Up when it lists its ports: waited for, up to a generous minute (not 100 tries).
        if (test::wait_for(
                [] {
                    return test::run_archet({"devices"}).out.find("jack 0: system") !=
                           std::string::npos;
                },
                std::chrono::milliseconds(60000)))
            return;
        FAIL() << "jackd did not start";
    }
    void TearDown() override {
        ::unsetenv("JACK_DEFAULT_SERVER");
        if (pid_ > 0) {
            ::kill(pid_, SIGTERM);
            ::waitpid(pid_, nullptr, 0);
        }
    }
    std::string name_;
    pid_t pid_ = -1;
};

}  // namespace archet::test
