#include "archet/common/printable_text.hpp"

#include <cstdint>

namespace archet {

namespace {

// The length of the valid, printable UTF-8 character at `text[i]`, or 0.
std::size_t printable_character(std::string_view text, std::size_t i) {
    const auto byte = [&](std::size_t k) { return static_cast<std::uint8_t>(text[k]); };
    const std::uint8_t lead = byte(i);
    if (lead < 0x80) return lead >= 0x20 && lead != 0x7f ? 1 : 0;
    std::size_t length = 0;
    std::uint32_t code = 0;
    if ((lead & 0xe0) == 0xc0)
        length = 2, code = lead & 0x1f;
    else if ((lead & 0xf0) == 0xe0)
        length = 3, code = lead & 0x0f;
    else if ((lead & 0xf8) == 0xf0)
        length = 4, code = lead & 0x07;
    else
        return 0;
    if (i + length > text.size()) return 0;
    for (std::size_t k = 1; k < length; ++k) {
        if ((byte(i + k) & 0xc0) != 0x80) return 0;
        code = (code << 6) | (byte(i + k) & 0x3f);
    }
    static constexpr std::uint32_t kShortest[] = {0, 0, 0x80, 0x800, 0x10000};
    const bool overlong = code < kShortest[length];
    const bool surrogate = code >= 0xd800 && code <= 0xdfff;
    const bool c1_control = code >= 0x80 && code < 0xa0;
    return overlong || surrogate || c1_control || code > 0x10ffff ? 0 : length;
}

}  // namespace

bool is_printable_text(std::string_view text) {
    for (std::size_t i = 0; i < text.size();) {
        const std::size_t n = printable_character(text, i);
        if (n == 0) return false;
        i += n;
    }
    return true;
}

std::string quoted_text(std::string_view text, std::size_t limit) {
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out = "\"";
    for (std::size_t i = 0; i < text.size();) {
        if (i >= limit) return out + "...\"";
        const std::size_t n = printable_character(text, i);
        if (n == 0) {
            const auto b = static_cast<std::uint8_t>(text[i++]);
            out += "\\x";
            out += kHex[b >> 4];
            out += kHex[b & 15];
        } else {
            if (text[i] == '"' || text[i] == '\\') out += '\\';
            out.append(text.substr(i, n));
            i += n;
        }
    }
    return out + "\"";
}

std::string printable_message(std::string_view text) {
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out;
    for (std::size_t i = 0; i < text.size();) {
        const std::size_t n = printable_character(text, i);
        if (n > 0 || text[i] == '\n' || text[i] == '\t') {
            out.append(text.substr(i, n > 0 ? n : 1));
            i += n > 0 ? n : 1;
            continue;
        }
        const auto b = static_cast<std::uint8_t>(text[i++]);
        out += "\\x";
        out += kHex[b >> 4];
        out += kHex[b & 15];
    }
    return out;
}

}  // namespace archet
