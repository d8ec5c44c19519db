#pragma once
// Where the shipped models and gestures are: beside an installed binary
// (<prefix>/share/archet, from <prefix>/bin), else the source tree it was built from.

#include <filesystem>

namespace archet::cli {

std::filesystem::path resource_folder();

}  // namespace archet::cli
