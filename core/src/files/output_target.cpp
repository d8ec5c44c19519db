#include "archet/files/output_target.hpp"

#include <unistd.h>

#include "archet/common/input_error.hpp"

namespace archet {

std::filesystem::path OutputTarget::temporary() const {
    return path.string() + ".tmp-" + std::to_string(static_cast<long>(::getpid()));
}

OutputTarget output_target(const std::filesystem::path& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);  // follows links
    if (ec || !fs::exists(status)) {
        // A dangling link is written through, onto the file it names.
        if (fs::is_symlink(fs::symlink_status(path, ec))) {
            const fs::path named = fs::read_symlink(path, ec);
            if (!ec) return {named.is_absolute() ? named : path.parent_path() / named, false};
        }
        return {path, false};
    }
    if (fs::is_directory(status))
        throw InputError(path.string(), "is a folder; give a file name inside it, e.g. " +
                                            (path / "out.wav").string());
    const fs::path resolved =
        fs::is_symlink(fs::symlink_status(path, ec)) ? fs::canonical(path, ec) : path;
    return {ec ? path : resolved, !fs::is_regular_file(status)};
}

}  // namespace archet
