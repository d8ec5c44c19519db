#include "archet/common/number_text.hpp"

#include <charconv>

namespace archet {

namespace {

constexpr int kMostTypedDigits = 9;  // a value typed by hand has fewer
constexpr int kComputedDigits = 6;   // enough to act on, few enough to read

int significant_digits(std::string_view text) {
    text = text.substr(0, text.find('e'));
    int digits = 0;
    bool leading = true;
    for (char c : text) {
        if (c < '0' || c > '9') continue;
        leading = leading && c == '0';
        digits += leading ? 0 : 1;
    }
    return digits;
}

}  // namespace

std::string format_number(double x) {
    char text[64];
    auto [end, error] = std::to_chars(text, text + sizeof text, x);
    if (error != std::errc{}) return "?";
    if (significant_digits({text, static_cast<std::size_t>(end - text)}) > kMostTypedDigits)
        end =
            std::to_chars(text, text + sizeof text, x, std::chars_format::general, kComputedDigits)
                .ptr;
    return {text, end};
}

std::string count_of(std::size_t count, std::string_view singular, std::string_view plural) {
    return std::to_string(count) + " " + std::string(count == 1 ? singular : plural);
}

}  // namespace archet
