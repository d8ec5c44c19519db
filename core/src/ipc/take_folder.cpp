#include "archet/ipc/take_folder.hpp"

#include <cstdint>
#include <system_error>

#include "archet/input_error.hpp"

namespace archet::ipc {

namespace fs = std::filesystem;

namespace {

// Printable: no control characters, and well-formed UTF-8 for the rest (a user's folder may
// be called "Café"); a random or binary payload fails one or the other.
bool printable(const std::string& s) {
    for (std::size_t i = 0; i < s.size();) {
        const auto c = static_cast<unsigned char>(s[i]);
        if (c < 0x20 || c == 0x7f) return false;
        if (c < 0x80) {
            ++i;
            continue;
        }
        std::size_t more = 0;
        std::uint32_t code = 0;
        if ((c & 0xe0) == 0xc0)
            more = 1, code = c & 0x1f;
        else if ((c & 0xf0) == 0xe0)
            more = 2, code = c & 0x0f;
        else if ((c & 0xf8) == 0xf0)
            more = 3, code = c & 0x07;
        else
            return false;
        if (i + more >= s.size()) return false;  // cut short
        for (std::size_t k = 1; k <= more; ++k) {
            const auto d = static_cast<unsigned char>(s[i + k]);
            if ((d & 0xc0) != 0x80) return false;
            code = (code << 6) | (d & 0x3f);
        }
        const std::uint32_t least[] = {0, 0x80, 0x800, 0x10000};
        if (code < least[more] || code > 0x10ffff || (code >= 0xd800 && code <= 0xdfff) ||
            (code >= 0x80 && code < 0xa0))  // overlong, out of range, surrogate, C1 control
            return false;
        i += more + 1;
    }
    return true;
}

bool inside(const fs::path& path, const fs::path& root) {
    auto p = path.begin();
    for (auto r = root.begin(); r != root.end(); ++r, ++p) {
        if (r->empty()) continue;  // a trailing separator
        if (p == path.end() || *p != *r) return false;
    }
    for (; p != path.end(); ++p)
        if (!p->empty()) return true;  // at least one part below the root
    return false;
}

}  // namespace

std::string quote_safely(const std::string& text, std::size_t limit) {
    static const char* hex = "0123456789abcdef";
    std::string q = "\"";
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (i == limit) return q + "...\"";
        const char ch = text[i];
        const auto c = static_cast<unsigned char>(ch);
        if (c >= 0x20 && c < 0x7f && c != '"' && c != '\\')
            q += ch;
        else if (c == '"' || c == '\\')
            q += '\\', q += ch;
        else
            q += "\\x", q += hex[c >> 4], q += hex[c & 15];
    }
    return q + "\"";
}

fs::path prepare_take_directory(const std::string& directory) {
    const std::string where = "take directory " + quote_safely(directory, 200);
    if (!printable(directory) || !fs::path(directory).is_absolute())
        throw InputError(where, "must be an absolute path of printable characters");
    std::error_code error;
    fs::create_directories(directory, error);
    const fs::path canonical = fs::canonical(directory, error);
    if (error || !fs::is_directory(canonical))
        throw InputError(where, "cannot be made or opened (" + error.message() +
                                    "): give a folder the engine may write");
    return canonical;
}

fs::path check_take_folder(const std::string& folder, const fs::path& root) {
    const std::string where = "take folder " + quote_safely(folder);
    if (root.empty())
        throw InputError(where,
                         "this engine has no take directory: start it with --takes DIR to record");
    if (!printable(folder))
        throw InputError(where, "has non-printable characters: name the folder in plain text");
    const fs::path path(folder);
    if (!path.is_absolute())
        throw InputError(
            where, "is relative: give an absolute path inside " + quote_safely(root.string()));
    for (const auto& part : path)
        if (part == "." || part == "..")
            throw InputError(where,
                             "has \".\" or \"..\" in it: give the folder's plain path "
                             "inside " +
                                 quote_safely(root.string()));
    std::error_code error;
    const fs::path resolved = fs::weakly_canonical(path, error);
    if (error || !inside(resolved, root))
        throw InputError(where, "is not inside the take directory " + quote_safely(root.string()) +
                                    " (symbolic links resolved): record under that folder");
    return path;
}

}  // namespace archet::ipc
