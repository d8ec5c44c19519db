#pragma once
// Model and gesture files: JSON with a "format" tag and a version. Loading parses and
// checks structure (types, keys, references are checked later by validate_model);
// saving writes a canonical form so that load → save round-trips exactly.

#include <filesystem>
#include <string>

#include "archet/model/gesture.hpp"
#include "archet/model/model.hpp"

namespace archet {

inline constexpr int kModelFormatVersion = 1;
inline constexpr int kGestureFormatVersion = 1;

/// Parses model JSON text. `source` names the file in error messages.
Model parse_model(const std::string& text, const std::string& source = "model");
std::string format_model(const Model& model);

Gesture parse_gesture(const std::string& text, const std::string& source = "gesture");
std::string format_gesture(const Gesture& gesture);

/// Whether the two parsers above read `text` with simdjson, the fast one, rather than nlohmann
/// (which reads what simdjson refuses or would read otherwise; docs/architecture.md): for the
/// tests and fuzzers that hold the two to the same result.
bool parses_fast(const std::string& text);

Model load_model_file(const std::filesystem::path& path);
Gesture load_gesture_file(const std::filesystem::path& path);

/// Reads a whole file; throws InputError naming the path when it cannot.
std::string read_text_file(const std::filesystem::path& path);
/// Writes through a temporary file in the same folder and renames it over the target, so
/// an existing file is never left half-written.
void write_file_atomically(const std::filesystem::path& path, const std::string& contents);

}  // namespace archet
