// The model loader on arbitrary bytes: parse, validate and, when valid, compile. Anything may
// be refused (InputError), nothing may crash, hang or read out of bounds. What simdjson parses
// must read as nlohmann reads it (a byte-order mark in front sends it to nlohmann).

#include <cstddef>
#include <cstdint>
#include <string>

#include "archet/common/input_error.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/physics/compiled_model.hpp"
#include "parsers_agree.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    if (!parsers_agree(text, [](const std::string& t) {
            return archet::format_model(archet::parse_model(t, "fuzz"));
        }))
        __builtin_trap();
    try {
        archet::Model model = archet::parse_model(text, "fuzz");
        archet::validate_model(model);
        if (model.mats.size() < 200) archet::compile(model);  // small ones: compile too
        // Saved and loaded again it must be the same model.
        const std::string saved = archet::format_model(model);
        if (archet::format_model(archet::parse_model(saved)) != saved) __builtin_trap();
    } catch (const archet::InputError&) {
    }
    return 0;
}
