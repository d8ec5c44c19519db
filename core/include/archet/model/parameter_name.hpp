#pragma once
// ELEMENT.PARAMETER: one parameter of one element, as --set, controls, takes and the engine
// command name it. Split in one place: here.

#include <string>
#include <string_view>

namespace archet {

struct ParameterName {
    std::string element;    ///< the id of a mass or link
    std::string parameter;  ///< its parameter's name, e.g. "mu_s"

    /// Splits at the last '.' (ids may hold dots, parameter names do not). Throws InputError
    /// at `where` (or at the text itself when empty) saying which half is missing.
    static ParameterName parse(std::string_view text, const std::string& where = {});

    std::string text() const { return element + "." + parameter; }
    bool operator==(const ParameterName&) const = default;
};

}  // namespace archet
