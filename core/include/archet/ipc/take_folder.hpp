#pragma once
// Where a StartTake command may record. The folder comes from another process in a command
// frame: before anything is created it must be a plain absolute path, printable, without "."
// or ".." parts, that lies (symbolic links resolved) inside the take directory the studio gave
// the engine at its start.

#include <filesystem>
#include <string>

namespace archet::ipc {

/// The take directory as the engine holds it: created if missing, then made canonical.
/// Throws InputError naming it when it is not absolute or cannot be made.
std::filesystem::path prepare_take_directory(const std::string& directory);

/// The folder to record into, or an InputError that quotes `folder` safely and says what to
/// change. `root` is the canonical take directory (empty: the engine has none, and refuses).
std::filesystem::path check_take_folder(const std::string& folder,
                                        const std::filesystem::path& root);

}  // namespace archet::ipc
