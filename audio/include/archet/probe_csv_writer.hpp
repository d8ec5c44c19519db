#pragma once
// Probe CSV: a header `time,<probe ids>` and one row per audio-rate sample. Written through
// a temporary file and renamed on close, like every file Archet writes.

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace archet {

class ProbeCsvWriter {
  public:
    ProbeCsvWriter(std::filesystem::path path, const std::vector<std::string>& columns);
    ~ProbeCsvWriter();
    ProbeCsvWriter(const ProbeCsvWriter&) = delete;
    ProbeCsvWriter& operator=(const ProbeCsvWriter&) = delete;

    /// One row: the time and `columns` values.
    void write_row(double time, const double* values);
    void close();

  private:
    std::filesystem::path path_, temp_;
    std::FILE* file_ = nullptr;
    std::size_t columns_ = 0;
};

}  // namespace archet
