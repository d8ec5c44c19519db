// An attack map's grid and its CSV: written by `archet attack`, read back to merge shards and
// to draw the diagram.

#include <algorithm>
#include <cmath>
#include <sstream>

#include "archet/analysis/attack.hpp"
#include "archet/common/input_error.hpp"

namespace archet {

namespace {

// Step i of `steps` from lo to hi, evenly in value or in its logarithm.
double grid_value(double lo, double hi, int steps, int i, bool log_axes) {
    if (steps <= 1) return lo;
    const double u = static_cast<double>(i) / (steps - 1);
    return log_axes ? lo * std::pow(hi / lo, u) : lo + (hi - lo) * u;
}

}  // namespace

std::size_t AttackGrid::size() const {
    return static_cast<std::size_t>(acceleration_steps) * static_cast<std::size_t>(force_steps);
}

double AttackGrid::acceleration(std::size_t index) const {
    const auto i = static_cast<int>(index / static_cast<std::size_t>(force_steps));
    return grid_value(acceleration_min, acceleration_max, acceleration_steps, i, log_axes);
}

double AttackGrid::force(std::size_t index) const {
    const auto i = static_cast<int>(index % static_cast<std::size_t>(force_steps));
    return grid_value(force_min, force_max, force_steps, i, log_axes);
}

std::string AttackGrid::describe() const {
    std::ostringstream s;
    s.precision(17);
    s << "acceleration=" << acceleration_min << ":" << acceleration_max << ":" << acceleration_steps
      << " force=" << force_min << ":" << force_max << ":" << force_steps
      << " axes=" << (log_axes ? "log" : "linear") << " position=" << position
      << " periods-max=" << periods_max;
    return s.str();
}

AttackGrid AttackGrid::parse(const std::string& text) {
    AttackGrid g;
    std::istringstream words(text);
    std::string word;
    auto range = [&](const std::string& value, double& lo, double& hi, int& steps) {
        char c1 = 0, c2 = 0;
        std::istringstream v(value);
        if (!(v >> lo >> c1 >> hi >> c2 >> steps) || c1 != ':' || c2 != ':' || !v.eof())
            throw InputError(value, "expected MIN:MAX:STEPS");
    };
    auto number = [](const std::string& key, const std::string& value) {
        std::istringstream v(value);
        double x = 0;
        if (!(v >> x) || !v.eof()) throw InputError(key, "\"" + value + "\" is not a number");
        return x;
    };
    while (words >> word) {
        const auto eq = word.find('=');
        const std::string key = word.substr(0, eq),
                          value = eq == std::string::npos ? "" : word.substr(eq + 1);
        if (key == "acceleration")
            range(value, g.acceleration_min, g.acceleration_max, g.acceleration_steps);
        else if (key == "force")
            range(value, g.force_min, g.force_max, g.force_steps);
        else if (key == "axes" && (value == "log" || value == "linear"))
            g.log_axes = value == "log";
        else if (key == "position")
            g.position = number(key, value);
        else if (key == "periods-max")
            g.periods_max = static_cast<int>(std::clamp(number(key, value), 0.0, 1e6));
        else
            throw InputError(word, "is not part of an attack grid");
    }
    return g;
}

std::string AttackGrid::problem() const {
    auto range = [](double lo, double hi, int steps, double most) {
        return lo > 0 && hi >= lo && hi <= most && steps >= 1;
    };
    if (!range(acceleration_min, acceleration_max, acceleration_steps, 1000))
        return "0 < MIN ≤ MAX ≤ 1000 and STEPS ≥ 1 for the acceleration (m/s²)";
    if (!range(force_min, force_max, force_steps, 100))
        return "0 < MIN ≤ MAX ≤ 100 and STEPS ≥ 1 for the force (N)";
    if (!(position >= 0 && position < 0.5)) return "a bow position β from 0 to 0.5";
    if (periods_max < 1 || periods_max > 1000) return "periods-max from 1 to 1000";
    return {};
}

std::string format_attack(const AttackMap& map) {
    const AttackGrid& grid = map.grid;
    std::ostringstream s;
    s.precision(10);
    s << "# archet-attack " << grid.describe() << "\n";
    s << "# the bow presses for " << kBowStart * 1000 << " ms, then the hand slides with "
      << "constant acceleration; periods are counted from the first slip to steady Helmholtz "
      << "motion\n# f1 = " << map.pitch << " Hz, the string's first mode\n";
    s << "index,acceleration_m_s2,force_n,attack,periods,slips,transient,first_slip_ms\n";
    for (const auto& p : map.points)
        s << p.index << "," << p.acceleration << "," << p.force << ","
          << to_string(p.transient.kind) << "," << p.transient.periods << "," << p.transient.slips
          << "," << to_string(p.transient.transient) << ","
          << (p.first_slip < 0 ? -1.0 : p.first_slip * 1000) << "\n";
    return s.str();
}

AttackMap parse_attack(const std::string& text, const std::string& source) {
    std::istringstream lines(text);
    std::string line;
    if (!std::getline(lines, line) || line.rfind("# archet-attack ", 0) != 0)
        throw InputError(source,
                         "is not an archet attack map (it must start with \"# archet-attack\")");
    AttackMap map;
    map.grid = AttackGrid::parse(line.substr(16));
    const AttackGrid& grid = map.grid;
    if (const std::string problem = grid.problem(); !problem.empty())
        throw InputError(source, "has a grid that cannot be: it needs " + problem);
    int row = 1;
    bool header = false;
    while (std::getline(lines, line)) {
        ++row;
        if (line.rfind("# f1 = ", 0) == 0) map.pitch = std::atof(line.c_str() + 7);
        if (line.empty() || line[0] == '#') continue;
        if (!header) {  // the column names
            header = true;
            continue;
        }
        std::istringstream cells(line);
        std::string cell;
        std::vector<std::string> c;
        while (std::getline(cells, cell, ',')) c.push_back(cell);
        if (c.size() < 8) throw InputError(source, "row " + std::to_string(row) + " is short");
        AttackPoint p;
        try {
            p.index = std::stoul(c[0]);
            p.acceleration = std::stod(c[1]), p.force = std::stod(c[2]);
            p.transient.kind = attack_kind_from_string(c[3]);
            p.transient.periods = std::stod(c[4]), p.transient.slips = std::stoi(c[5]);
            p.transient.transient = transient_from_string(c[6]);
            const double first_ms = std::stod(c[7]);
            p.first_slip = first_ms < 0 ? -1.0 : first_ms / 1000;
        } catch (const std::logic_error&) {
            throw InputError(source,
                             "row " + std::to_string(row) + " has a value that is not a number");
        }
        p.transient.decided = true;
        if (p.index >= grid.size())
            throw InputError(source, "row " + std::to_string(row) + " is outside the grid");
        map.points.push_back(p);
    }
    if (!(map.pitch > 0)) throw InputError(source, "does not say the string's pitch (# f1 = … Hz)");
    return map;
}

}  // namespace archet
