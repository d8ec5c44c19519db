#include "archet/files/state_file.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "archet/common/input_error.hpp"
#include "archet/common/input_limits.hpp"
#include "archet/common/number_text.hpp"
#include "archet/common/printable_text.hpp"
#include "archet/files/model_file.hpp"

namespace archet {

namespace {
constexpr const char* kMagic = "archet-state 1";
static_assert(std::endian::native == std::endian::little, "state files are little-endian");
}  // namespace

void write_state_file(const std::filesystem::path& path, const std::vector<double>& state) {
    std::string bytes = std::string(kMagic) + " " + std::to_string(state.size()) + "\n";
    const std::size_t header = bytes.size();
    bytes.resize(header + state.size() * sizeof(double));
    std::memcpy(bytes.data() + header, state.data(), state.size() * sizeof(double));
    write_file_atomically(path, bytes);
}

std::vector<double> read_state_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path.string(), "cannot open the state file");
    std::string line;
    for (char c = 0; line.size() < 200 && in.get(c) && c != '\n';) line += c;  // bounded
    std::istringstream words(line);
    std::string format, version;
    std::size_t count = 0;
    if (!(words >> format >> version >> count) || format + " " + version != kMagic)
        throw InputError(path.string(), "is not an Archet state file (it starts " +
                                            quoted_text(line.substr(0, 40)) + ")");
    const auto start = in.tellg();
    in.seekg(0, std::ios::end);
    const auto bytes = static_cast<std::size_t>(in.tellg() - start);
    if (count > limits::kFileBytes / sizeof(double) || bytes != count * sizeof(double))
        throw InputError(path.string(), "is truncated or damaged: it announces " +
                                            count_of(count, "number", "numbers") + " but holds " +
                                            count_of(bytes, "byte", "bytes"));
    in.seekg(start);
    std::vector<double> state(count);
    in.read(reinterpret_cast<char*>(state.data()), static_cast<std::streamsize>(bytes));
    if (!in) throw InputError(path.string(), "could not be read to the end");
    for (std::size_t i = 0; i < state.size(); ++i)
        if (!std::isfinite(state[i]))
            throw InputError(path.string(), "number #" + std::to_string(i + 1) +
                                                " is not finite; the state is damaged");
    return state;
}

}  // namespace archet
