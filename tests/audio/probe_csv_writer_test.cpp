// The probe CSV's numbers: every one written as printf's "%.9g" writes it (the take reader,
// users' scripts and earlier files read them so), rows and header as before.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "archet/probe_csv_writer.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

std::string printf_row(double time, const std::vector<double>& values) {
    char number[64];
    std::snprintf(number, sizeof number, "%.9g", time);
    std::string row = number;
    for (double v : values) {
        std::snprintf(number, sizeof number, ",%.9g", v);
        row += number;
    }
    return row + "\n";
}

TEST(ProbeCsvWriter, WritesEveryNumberAsPrintfWritesItWithNineDigits) {
    const std::filesystem::path folder = test::temp_dir("probe-csv");
    const std::filesystem::path path = folder / "probes.csv";
    constexpr double kInf = std::numeric_limits<double>::infinity();
    std::vector<std::vector<double>> rows = {
        {0.0, -0.0, 1.0, -1.0},
        {5e-324, 1e-320, 2.2250738585072014e-308, 1.7976931348623157e308},
        {kInf, -kInf, std::nan(""), -std::nan("")},
        {123456789.0, 1234567890.0, 1e-5, 9.999999995e-5},
    };
    std::mt19937_64 bits(15);
    std::uniform_real_distribution<double> unit(-1, 1);
    for (int i = 0; i < 2000; ++i)  // any bits, and the small motions probes read
        rows.push_back({std::bit_cast<double>(bits()), std::bit_cast<double>(bits()),
                        unit(bits) * 1e-3, unit(bits)});
    std::string expected = "time,a,b,c,d\n";
    {
        ProbeCsvWriter csv(path, {"a", "b", "c", "d"});
        for (std::size_t i = 0; i < rows.size(); ++i) {
            const double time = static_cast<double>(i + 1) / 48000.0;
            csv.write_row(time, rows[i].data());
            expected += printf_row(time, rows[i]);
        }
        csv.close();
    }
    std::ifstream in(path, std::ios::binary);
    std::stringstream written;
    written << in.rdbuf();
    EXPECT_EQ(written.str(), expected);
}

TEST(ProbeCsvWriter, AFileWithNoColumnsHasTheTimeAlone) {
    const std::filesystem::path folder = test::temp_dir("probe-csv-none");
    const std::filesystem::path path = folder / "probes.csv";
    {
        ProbeCsvWriter csv(path, {});
        csv.write_row(0.5, nullptr);
        csv.close();
    }
    std::ifstream in(path, std::ios::binary);
    std::stringstream written;
    written << in.rdbuf();
    EXPECT_EQ(written.str(), "time\n0.5\n");
}

}  // namespace
}  // namespace archet
