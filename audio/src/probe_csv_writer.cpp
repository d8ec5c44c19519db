#include "archet/probe_csv_writer.hpp"

#include <unistd.h>

#include <charconv>
#include <system_error>

#include "archet/common/input_error.hpp"
#include "archet/files/output_target.hpp"

namespace archet {

ProbeCsvWriter::ProbeCsvWriter(std::filesystem::path path, const std::vector<std::string>& columns,
                               WriteMode mode)
    : path_(std::move(path)),
      mode_(mode),
      columns_(columns.size()),
      row_((columns.size() + 1) * kNumberBytes + 1) {
    // Direct: "x" refuses a file that exists (a take never overwrites one). Safe: a device or
    // FIFO (--probes /dev/null) is written in place, never renamed over.
    const char* how = "wx";
    if (mode_ == WriteMode::Safe) {
        const OutputTarget target = output_target(path_);
        temp_ = target.in_place ? target.path : target.temporary();
        final_ = target.path;
        if (target.in_place) mode_ = WriteMode::Direct;
        how = "w";
    } else {
        temp_ = final_ = path_;
    }
    file_ = std::fopen(temp_.c_str(), how);
    if (!file_)
        throw InputError(path_.string(), "cannot write the probe file (is the folder writable?)");
    std::fputs("time", file_);
    for (const auto& c : columns) std::fprintf(file_, ",%s", c.c_str());
    std::fputc('\n', file_);
}

ProbeCsvWriter::~ProbeCsvWriter() {
    if (file_) {
        std::fclose(file_);
        std::error_code ignored;
        if (mode_ == WriteMode::Safe) std::filesystem::remove(temp_, ignored);
    }
}

void ProbeCsvWriter::flush() {
    if (file_) std::fflush(file_);
}

namespace {

// A number as printf's "%.9g" writes it: std::to_chars with the same format and precision is
// specified to give the same characters, several times faster. Returns the end.
char* nine_digits(char* at, char* end, double value) {
    return std::to_chars(at, end, value, std::chars_format::general, 9).ptr;
}

}  // namespace

void ProbeCsvWriter::write_row(double time, const double* values) {
    char* at = row_.data();
    char* const end = row_.data() + row_.size();
    at = nine_digits(at, end, time);
    for (std::size_t i = 0; i < columns_; ++i) {
        *at++ = ',';
        at = nine_digits(at, end, values[i]);
    }
    *at++ = '\n';
    std::fwrite(row_.data(), 1, static_cast<std::size_t>(at - row_.data()), file_);
}

void ProbeCsvWriter::close() {
    if (!file_) return;
    const bool failed = std::ferror(file_) != 0;
    const bool close_failed = std::fclose(file_) != 0;
    file_ = nullptr;
    std::error_code ec;
    if (failed || close_failed) {
        if (mode_ == WriteMode::Safe) std::filesystem::remove(temp_, ec);
        throw InputError(path_.string(), "could not write the probe file (disk full?)");
    }
    if (mode_ == WriteMode::Direct) return;
    std::filesystem::rename(temp_, final_, ec);
    if (ec) {
        std::filesystem::remove(temp_, ec);
        throw InputError(path_.string(), "cannot move the probe file into place: " + ec.message());
    }
}

}  // namespace archet
