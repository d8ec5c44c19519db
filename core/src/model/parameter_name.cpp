#include "archet/model/parameter_name.hpp"

#include "archet/common/input_error.hpp"
#include "archet/common/printable_text.hpp"

namespace archet {

ParameterName ParameterName::parse(std::string_view text, const std::string& where) {
    const std::string whole(text);
    const std::string at = where.empty() ? quoted_text(whole) : where;
    const auto dot = whole.rfind('.');
    const char* missing = nullptr;
    if (whole.empty())
        missing = "is empty";
    else if (dot == std::string::npos)
        missing = "has no '.' between element and parameter";
    else if (dot == 0)
        missing = "names no element before the '.'";
    else if (dot + 1 == whole.size())
        missing = "names no parameter after the '.'";
    if (missing)
        throw InputError(at, (where.empty() ? "" : quoted_text(whole) + " ") + missing +
                                 "; expected ELEMENT.PARAMETER, e.g. friction.mu_s");
    return {whole.substr(0, dot), whole.substr(dot + 1)};
}

}  // namespace archet
