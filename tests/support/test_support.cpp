#include "test_support.hpp"

#include <sys/wait.h>
#include <unistd.h>
#include <thread>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>

namespace archet::test {

BowedStringOptions paper_string_options() {
    BowedStringOptions o;
    o.pitch = 220, o.paper = true;
    return o;
}

std::filesystem::path source_dir() {
    return ARCHET_SOURCE_DIR;
}
std::filesystem::path resource(const std::string& relative) {
    return source_dir() / "resources" / relative;
}
std::filesystem::path test_data(const std::string& relative) {
    return source_dir() / "tests" / "data" / relative;
}

namespace {
// The folders this test process made, removed when it exits normally; a crash leaves them to
// look at, and so does ARCHET_KEEP_TEST_FILES=1. Only the process that made them removes
// them: a forked child that exits must not take its parent's files.
class MadeFolders {
  public:
    void add(const std::filesystem::path& dir) {
        const std::lock_guard<std::mutex> lock(mutex_);
        paths_.insert(dir);
    }
    ~MadeFolders() {
        if (::getpid() != maker_ || std::getenv("ARCHET_KEEP_TEST_FILES")) return;
        for (const auto& dir : paths_) {
            std::error_code ignored;
            std::filesystem::remove_all(dir, ignored);
        }
    }

  private:
    std::mutex mutex_;
    std::set<std::filesystem::path> paths_;
    const pid_t maker_ = ::getpid();
};
MadeFolders& made_folders() {
    static MadeFolders folders;
    return folders;
}
}  // namespace

std::filesystem::path temp_dir(const std::string& name) {
    // A parameterised test's name has a slash ("Name/0"): one folder, not one inside another.
    std::string flat = name;
    std::replace(flat.begin(), flat.end(), '/', '-');
    auto dir = std::filesystem::temp_directory_path() /
               ("archet-test-" + flat + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    made_folders().add(dir);
    return dir;
}

namespace {
std::string quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}
}  // namespace

bool wait_for(const std::function<bool()>& done, std::chrono::milliseconds limit) {
    const auto end = std::chrono::steady_clock::now() + limit;
    while (std::chrono::steady_clock::now() < end) {
        if (done()) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return done();
}

std::string read_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<double> probe_column(const std::filesystem::path& csv, const std::string& name) {
    std::istringstream in(read_file(csv));
    std::string line, cell;
    std::getline(in, line);
    int column = -1, i = 0;
    for (std::istringstream header(line); std::getline(header, cell, ','); ++i)
        if (cell == name) column = i;
    std::vector<double> values;
    while (column >= 0 && std::getline(in, line)) {
        std::istringstream row(line);
        for (int c = 0; c <= column; ++c) std::getline(row, cell, ',');
        values.push_back(std::stod(cell));
    }
    return values;
}

CommandResult run_command(const std::vector<std::string>& arguments) {
    const auto dir = temp_dir("run");
    std::string command;
    for (const auto& a : arguments) command += (command.empty() ? "" : " ") + quote(a);
    command += " >" + quote((dir / "out").string()) + " 2>" + quote((dir / "err").string()) +
               " </dev/null";
    const int raw = std::system(command.c_str());
    CommandResult r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
    r.out = read_file(dir / "out");
    r.err = read_file(dir / "err");
    std::filesystem::remove_all(dir);
    return r;
}

CommandResult run_archet(const std::vector<std::string>& arguments) {
    std::vector<std::string> command{ARCHET_BINARY};
    command.insert(command.end(), arguments.begin(), arguments.end());
    return run_command(command);
}

double zero_crossing_frequency(const std::vector<double>& x, double fs) {
    double first = -1, last = -1;
    int crossings = 0;
    for (std::size_t i = 1; i < x.size(); ++i) {
        if (x[i - 1] < 0 && x[i] >= 0) {
            const double t = (static_cast<double>(i - 1) + (-x[i - 1]) / (x[i] - x[i - 1])) / fs;
            if (first < 0)
                first = t;
            else
                ++crossings;
            last = t;
        }
    }
    return crossings > 0 ? crossings / (last - first) : 0.0;
}

double sinusoid_frequency(const std::vector<double>& x, double fs) {
    double cross = 0, square = 0;
    for (std::size_t n = 1; n + 1 < x.size(); ++n)
        cross += x[n] * (x[n + 1] + x[n - 1]), square += x[n] * x[n];
    return std::acos(cross / (2 * square)) * fs / (2 * std::acos(-1.0));
}

Mat mass(const std::string& id, double m, double position, const std::string& rate) {
    Mat x;
    x.id = id, x.kind = MatKind::Mass, x.mass = m, x.position = position, x.rate = rate;
    return x;
}

Mat fixed(const std::string& id, double position, const std::string& rate) {
    Mat x;
    x.id = id, x.kind = MatKind::Fixed, x.position = position, x.rate = rate;
    return x;
}

Lia spring_damper(const std::string& id, const std::string& from, const std::string& to, double k,
                  double z, const std::string& rate) {
    Lia l;
    l.id = id, l.kind = LiaKind::SpringDamper, l.from = from, l.to = to, l.stiffness = k,
    l.damping = z, l.rate = rate;
    return l;
}

Model chain(int n, double m, double k, double z, double fs) {
    Model model;
    model.name = "chain";
    model.sample_rate = fs;
    model.mats.push_back(fixed("end_a"));
    for (int i = 1; i <= n; ++i) model.mats.push_back(mass("m" + std::to_string(i), m));
    model.mats.push_back(fixed("end_b"));
    for (int i = 0; i <= n; ++i)
        model.lias.push_back(spring_damper("l" + std::to_string(i),
                                           i == 0 ? "end_a" : "m" + std::to_string(i),
                                           i == n ? "end_b" : "m" + std::to_string(i + 1), k, z));
    return model;
}

Model plucked_chain(int n) {
    Model plucked = chain(n, 1e-4, 1e3, 1e-4);
    plucked.name = "plucked-chain";
    for (int i = 1; i <= n; ++i)
        plucked.mats[static_cast<std::size_t>(i)].position =
            1e-3 * std::min(i, n + 1 - i) / ((n + 1) / 2.0);
    plucked.outputs = {{"m1", Output::Signal::Position, 1.0}};
    return plucked;
}

}  // namespace archet::test
