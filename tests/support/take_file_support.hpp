#pragma once
// Reading a take's files back in the take tests (header-only: only the suites that link
// libsndfile include it).

#include <sndfile.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <system_error>
#include <vector>

#include "test_support.hpp"

namespace archet::test {

/// The file's size in bytes, 0 when it does not exist (yet).
inline std::uintmax_t size_of(const std::filesystem::path& file) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(file, ec);
    return ec ? 0 : size;
}

/// All the samples of a sound file, as integers (exact for 24-bit PCM).
inline std::vector<int> samples_of(const std::filesystem::path& wav) {
    SF_INFO info{};
    SNDFILE* f = sf_open(wav.c_str(), SFM_READ, &info);
    if (!f) return {};
    std::vector<int> samples(static_cast<std::size_t>(info.frames));
    samples.resize(static_cast<std::size_t>(sf_read_int(f, samples.data(), info.frames)));
    sf_close(f);
    return samples;
}

/// The file as JSON, or a discarded value when it is missing or damaged.
inline nlohmann::json read_json(const std::filesystem::path& file) {
    return nlohmann::json::parse(read_file(file), nullptr, false);
}

}  // namespace archet::test
