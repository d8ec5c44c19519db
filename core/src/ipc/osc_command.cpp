#include "archet/ipc/osc_command.hpp"

#include <cmath>
#include <optional>

#include "archet/common/input_limits.hpp"
#include "archet/common/number_text.hpp"
#include "archet/common/printable_text.hpp"

namespace archet::ipc {

namespace {

using Kind = OscCommand::Kind;

bool is_number(char type) {
    return type == 'f' || type == 'd' || type == 'i' || type == 'h';
}

// The types a message carried, as OSC writes them (",fs"), for messages.
std::string type_tags(std::span<const OscArgument> arguments) {
    std::string tags = ",";
    for (const auto& a : arguments) tags += a.type;
    return tags;
}

// One number in [low, high], or why not.
std::variant<double, std::string> one_number(std::string_view path,
                                             std::span<const OscArgument> arguments, double low,
                                             double high, const char* what) {
    const std::string where(path);
    if (arguments.size() != 1 || !is_number(arguments[0].type))
        return where + " takes one number (" + what + "), not " + type_tags(arguments);
    const double v = arguments[0].number;
    if (!std::isfinite(v)) return where + ": the number must be finite";
    if (v < low || v > high)
        return where + ": " + format_number(v) + " is out of range; send " + format_number(low) +
               " to " + format_number(high) + " (" + what + ")";
    return v;
}

}  // namespace

std::string_view osc_address_space() {
    return "/archet/bow/slide f (m), /archet/bow/press f (m), /archet/finger f (0 to 1), "
           "/archet/finger/pressure f (0 to 1), /archet/param s f (ELEMENT.PARAM, value), "
           "/archet/record s (start or stop)";
}

std::variant<OscCommand, std::string> decode_osc(std::string_view path,
                                                 std::span<const OscArgument> arguments) {
    const std::string where = quoted_text(path, 64);
    struct Number {
        std::string_view path;
        Kind kind;
        double low, high;
        const char* what;
    };
    static const Number numbers[] = {
        {"/archet/bow/slide", Kind::Slide, -limits::kPosition, limits::kPosition, "m"},
        {"/archet/bow/press", Kind::Press, -limits::kPress, limits::kPress, "m"},
        {"/archet/finger", Kind::Finger, 0.0, 1.0, "the finger's position"},
        {"/archet/finger/pressure", Kind::FingerPressure, 0.0, 1.0, "the finger's pressure"}};
    for (const Number& n : numbers) {
        if (path != n.path) continue;
        auto v = one_number(where, arguments, n.low, n.high, n.what);
        if (auto* why = std::get_if<std::string>(&v)) return *why;
        return OscCommand{n.kind, std::get<double>(v), {}};
    }
    if (path == "/archet/param") {
        if (arguments.size() != 2 || arguments[0].type != 's' || !is_number(arguments[1].type))
            return where + " takes a name and a number (,sf: ELEMENT.PARAM and its value), not " +
                   type_tags(arguments);
        OscCommand c{Kind::Parameter, arguments[1].number, {}};
        try {
            c.parameter = ParameterName::parse(arguments[0].text, where);
        } catch (const std::exception& e) {
            return printable_message(e.what());
        }
        if (!std::isfinite(c.value)) return where + ": the value must be finite";
        return c;
    }
    if (path == "/archet/record") {
        if (arguments.size() == 1 && arguments[0].type == 's') {
            if (arguments[0].text == "start") return OscCommand{Kind::RecordStart, 0, {}};
            if (arguments[0].text == "stop") return OscCommand{Kind::RecordStop, 0, {}};
        }
        return where + " takes \"start\" or \"stop\"";
    }
    return "unknown address " + where + "; Archet listens to " + std::string(osc_address_space());
}

}  // namespace archet::ipc
