#pragma once
// Shared by the commands that take a MODEL: load, apply --set, validate.

#include <string>
#include <vector>

#include "archet/model/model.hpp"

namespace archet::cli {

/// Throws InputError (exit 2) for a missing, malformed or invalid model.
Model load_validated_model(const std::string& path, const std::vector<std::string>& assignments,
                           double sample_rate = 0);

}  // namespace archet::cli
