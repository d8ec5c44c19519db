#pragma once
// Where a command writes its result. A new or regular file is written beside itself and
// renamed into place (the user's file is never half-written); a device or a FIFO (/dev/null,
// a pipe) is written in place, since renaming over it would replace the device node with a
// plain file; a folder is refused. A symbolic link is followed, so the link stays a link.

#include <filesystem>
#include <string>

namespace archet {

struct OutputTarget {
    std::filesystem::path path;  ///< the file to end up with (a link resolved)
    bool in_place = false;       ///< write straight into `path` (not a regular file)
    /// The temporary file to write before renaming it onto `path` (unused when in_place).
    std::filesystem::path temporary() const;
};

/// Throws InputError naming `path` when it is a folder.
OutputTarget output_target(const std::filesystem::path& path);

}  // namespace archet
