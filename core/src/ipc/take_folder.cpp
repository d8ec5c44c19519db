#include "archet/ipc/take_folder.hpp"

#include <cstdint>
#include <system_error>

#include "archet/common/input_error.hpp"
#include "archet/common/printable_text.hpp"

namespace archet::ipc {

namespace fs = std::filesystem;

namespace {

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

fs::path prepare_take_directory(const std::string& directory) {
    const std::string where = "take directory " + quoted_text(directory, 200);
    if (!is_printable_text(directory) || !fs::path(directory).is_absolute())
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
    const std::string where = "take folder " + quoted_text(folder);
    if (root.empty())
        throw InputError(where,
                         "this engine has no take directory: start it with --takes DIR to record");
    if (!is_printable_text(folder))
        throw InputError(where, "has non-printable characters: name the folder in plain text");
    const fs::path path(folder);
    if (!path.is_absolute())
        throw InputError(where,
                         "is relative: give an absolute path inside " + quoted_text(root.string()));
    for (const auto& part : path)
        if (part == "." || part == "..")
            throw InputError(where,
                             "has \".\" or \"..\" in it: give the folder's plain path "
                             "inside " +
                                 quoted_text(root.string()));
    std::error_code error;
    const fs::path resolved = fs::weakly_canonical(path, error);
    if (error || !inside(resolved, root))
        throw InputError(where, "is not inside the take directory " + quoted_text(root.string()) +
                                    " (symbolic links resolved): record under that folder");
    return resolved;
}

}  // namespace archet::ipc
