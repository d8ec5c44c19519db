#pragma once
// Helpers shared by the test suites: paths, running the real `archet` binary, and small
// models built in code.

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "archet/builders/bowed_string.hpp"
#include "archet/model/model.hpp"
#include "archet/physics/simulation.hpp"

namespace archet::test {

std::filesystem::path source_dir();
std::filesystem::path resource(const std::string& relative);   ///< under resources/
std::filesystem::path test_data(const std::string& relative);  ///< under tests/data/

/// A fresh empty folder for one test, removed when the test process exits normally (kept
/// after a crash, or with ARCHET_KEEP_TEST_FILES=1).
std::filesystem::path temp_dir(const std::string& name);

struct CommandResult {
    int status = -1;
    std::string out, err;
};
/// Runs a program with the arguments (each shell-quoted), capturing both streams.
CommandResult run_command(const std::vector<std::string>& arguments);
/// The same for the `archet` built here.
CommandResult run_archet(const std::vector<std::string>& arguments);

std::string read_file(const std::filesystem::path& path);
/// The column `name` of a probes CSV (a take's probes.csv, render --probes): empty without it.
std::vector<double> probe_column(const std::filesystem::path& csv, const std::string& name);

/// Polls `done` every 2 ms until it holds or `limit` passes; returns its last answer.
bool wait_for(const std::function<bool()>& done, std::chrono::milliseconds limit);

/// Zero-crossing frequency (Hz) of a signal sampled at fs, with linear interpolation,
/// from the first to the last upward crossing.
double zero_crossing_frequency(const std::vector<double>& signal, double fs);

/// Frequency (Hz) of a pure sampled sinusoid from its recurrence x[n+1] + x[n−1] = 2cos(ΩT)x[n],
/// by least squares: exact to round-off at any number of samples per period.
double sinusoid_frequency(const std::vector<double>& signal, double fs);

/// True in the AddressSanitizer and ThreadSanitizer builds. There building and analysing the
/// 110 Hz strings (about two hundred masses: eigenvalues of their update matrix, many times)
/// runs twenty times slower than in the release build, up to three minutes for one test: their
/// suites check that size in the release build, and the same code at 220-880 Hz under both.
constexpr bool kUnderSanitizer =
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
    true;
#else
    false;
#endif
/// Why a 110 Hz instance skips under a sanitizer.
inline constexpr const char* kLargeStringUnderSanitizer =
    "the 110 Hz string is checked in the release build: under a sanitizer its eigen-analysis "
    "takes minutes, and the 220-880 Hz instances run the same code";

/// The paper's 60-mass 220 Hz string: a small, quick model for tests about something else.
BowedStringOptions paper_string_options();

/// A MAT or LIA in one line.
Mat mass(const std::string& id, double m, double position = 0, const std::string& rate = "audio");
Mat fixed(const std::string& id, double position = 0, const std::string& rate = "audio");
Lia spring_damper(const std::string& id, const std::string& from, const std::string& to, double k,
                  double z, const std::string& rate = "audio");

/// A fixed–fixed homogeneous chain of n masses (ids m1..mn, ends end_a and end_b).
Model chain(int n, double m, double k, double z, double fs = 48000);

/// A chain of n masses of 0.1 g joined by 1 kN/m springs, plucked 1 mm at its middle into a
/// triangle and left to ring; its sound is the first mass's position. Without a bow, every MAT
/// of it is the string (string_points()).
Model plucked_chain(int n);

}  // namespace archet::test
