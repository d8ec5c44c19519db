#include "resource_folder.hpp"

#include <system_error>

namespace archet::cli {

std::filesystem::path resource_folder() {
    std::error_code ec;
    const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const auto installed = self.parent_path().parent_path() / "share" / "archet";
        if (std::filesystem::is_directory(installed / "models", ec)) return installed;
    }
    return ARCHET_RESOURCE_DIR;
}

}  // namespace archet::cli
