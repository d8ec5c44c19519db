// The take reader on arbitrary bytes: take.json, parameters.json, and what recovering an
// interrupted take parses (the gesture and parameter streams, take.wav's header). The first
// byte chooses which: 't', 'p', 'g', 's', 'w' (any other byte: its value modulo 5).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "archet/common/input_error.hpp"
#include "archet/files/take_file.hpp"
#include "archet/files/take_recovery.hpp"

namespace {

void take(const std::string& text) {
    const archet::TakeDescription t = archet::parse_take(text, "fuzz");
    if (!(t.sample_rate >= 1000 && t.sample_rate <= 1e6) || !std::isfinite(t.peak) || t.peak < 0)
        __builtin_trap();
    if (t.interrupted == t.interrupted_by.empty()) __builtin_trap();
    if (t.scheme < 1 || t.scheme > archet::kSchemeRevision) __builtin_trap();
    // What it writes, it reads back the same.
    const archet::TakeDescription again = archet::parse_take(archet::format_take(t), "again");
    if (again.frames != t.frames || again.start_tick != t.start_tick ||
        again.complete != t.complete || again.interrupted_by != t.interrupted_by ||
        again.clipped_samples != t.clipped_samples || again.peak != t.peak ||
        again.scheme != t.scheme)
        __builtin_trap();
}

void parameters(const std::string& text) {
    const auto changes = archet::parse_parameter_changes(text, "fuzz");
    for (std::size_t i = 0; i < changes.size(); ++i)
        if (changes[i].glide_samples < 1 || (i > 0 && changes[i].tick < changes[i - 1].tick))
            __builtin_trap();
}

void gesture_stream(const std::string& text) {
    const auto keyframes = archet::parse_gesture_stream(text, "fuzz");
    for (std::size_t i = 0; i < keyframes.size(); ++i) {
        const auto& k = keyframes[i];
        if (!std::isfinite(k.time) || !std::isfinite(k.slide) || !std::isfinite(k.press))
            __builtin_trap();
        if (i > 0 && !(k.time > keyframes[i - 1].time)) __builtin_trap();
    }
    std::string written;
    for (const auto& k : keyframes) written += archet::format_gesture_line(k);
    if (archet::parse_gesture_stream(written, "again") != keyframes) __builtin_trap();
}

void parameter_stream(const std::string& text) {
    const auto changes = archet::parse_parameter_stream(text, "fuzz");
    for (std::size_t i = 0; i < changes.size(); ++i)
        if (changes[i].glide_samples < 1 || !std::isfinite(changes[i].value) ||
            (i > 0 && changes[i].tick < changes[i - 1].tick))
            __builtin_trap();
}

void wav(const std::string& bytes) {
    // The file as it is, and as if samples had been written past what the header counts.
    for (const std::uint64_t extra : {std::uint64_t{0}, std::uint64_t{1} << 20}) {
        const std::uint64_t size = bytes.size() + extra;
        const archet::WavLayout w = archet::parse_wav_layout(bytes, size, "fuzz");
        if (w.block_align == 0 || w.data_offset > size ||
            w.data_offset + w.frames * w.block_align > size)
            __builtin_trap();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
    void (*const readers[])(const std::string&) = {take, parameters, gesture_stream,
                                                   parameter_stream, wav};
    int which = data[0] % 5;
    switch (data[0]) {
        case 't':
            which = 0;
            break;
        case 'p':
            which = 1;
            break;
        case 'g':
            which = 2;
            break;
        case 's':
            which = 3;
            break;
        case 'w':
            which = 4;
            break;
        default:
            break;
    }
    try {
        readers[which](text);
    } catch (const archet::InputError&) {
    }
    return 0;
}
