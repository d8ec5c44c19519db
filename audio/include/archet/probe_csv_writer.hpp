#pragma once
// Probe CSV: a header `time,<probe ids>` and one row per audio-rate sample. Written through
// a temporary file and renamed on close, like every file Archet writes; or, for a take,
// straight into a new file, flushed as it goes so that it can be read while it grows.

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "archet/sound_file_writer.hpp"

namespace archet {

class ProbeCsvWriter {
  public:
    ProbeCsvWriter(std::filesystem::path path, const std::vector<std::string>& columns,
                   WriteMode mode = WriteMode::Safe);
    ~ProbeCsvWriter();
    ProbeCsvWriter(const ProbeCsvWriter&) = delete;
    ProbeCsvWriter& operator=(const ProbeCsvWriter&) = delete;

    /// One row: the time and `columns` values.
    void write_row(double time, const double* values);
    /// Hands the rows written so far to the system (Direct: readable by others from now on).
    void flush();
    void close();

  private:
    std::filesystem::path path_, temp_, final_;  ///< as given, written, renamed onto
    WriteMode mode_;
    std::FILE* file_ = nullptr;
    std::size_t columns_ = 0;
    /// The longest "%.9g" ("-1.23456789e-308") and its comma, with room to spare.
    static constexpr std::size_t kNumberBytes = 32;
    std::vector<char> row_;  ///< a row's characters, handed to stdio at once
};

}  // namespace archet
