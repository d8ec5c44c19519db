#include "archet/files/take_recovery.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "archet/common/input_error.hpp"
#include "archet/files/model_file.hpp"

namespace archet {

namespace {

using Json = nlohmann::ordered_json;

std::uint32_t u32(std::string_view b, std::size_t at) {
    return static_cast<std::uint32_t>(static_cast<unsigned char>(b[at])) |
           static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 1])) << 8 |
           static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 2])) << 16 |
           static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 3])) << 24;
}

std::uint16_t u16(std::string_view b, std::size_t at) {
    return static_cast<std::uint16_t>(static_cast<unsigned char>(b[at]) |
                                      static_cast<unsigned char>(b[at + 1]) << 8);
}

// The complete lines of a stream, each with its number (from 1); the last is left out when
// its newline is missing: the recorder was writing it.
template <typename Each>
void for_each_line(std::string_view text, const std::string& source, Each each) {
    std::size_t start = 0, number = 0;
    for (std::size_t end; (end = text.find('\n', start)) != std::string_view::npos;
         start = end + 1) {
        ++number;
        const std::string where = source + ": line " + std::to_string(number);
        Json line;
        try {
            line = Json::parse(text.substr(start, end - start));
        } catch (const Json::exception& e) {
            throw InputError(where, std::string("is not valid JSON: ") + e.what());
        }
        if (!line.is_array()) throw InputError(where, "must be a JSON array");
        each(line, where);
    }
}

double finite(const Json& v, const std::string& where, const char* what) {
    if (!v.is_number() || !std::isfinite(v.get<double>()))
        throw InputError(where, std::string(what) + " must be a finite number");
    return v.get<double>();
}

void write_u32(std::fstream& f, std::uint64_t at, std::uint32_t value) {
    const char bytes[4] = {static_cast<char>(value & 0xFF), static_cast<char>(value >> 8 & 0xFF),
                           static_cast<char>(value >> 16 & 0xFF),
                           static_cast<char>(value >> 24 & 0xFF)};
    f.seekp(static_cast<std::streamoff>(at));
    f.write(bytes, 4);
}

// Makes take.wav's header count the whole frames it holds, and cuts a frame left half
// written. Only the two size fields change: the samples stay as they were recorded.
void repair_wav(const std::filesystem::path& wav, const WavLayout& layout,
                std::uint64_t file_size) {
    const std::uint64_t data = layout.frames * layout.block_align;
    const std::uint64_t end = layout.data_offset + data;
    if (layout.header_frames == layout.frames && end == file_size) return;
    std::error_code ec;
    if (end < file_size) std::filesystem::resize_file(wav, end, ec);
    if (ec) throw InputError(wav.string(), "cannot be repaired: " + ec.message());
    std::fstream f(wav, std::ios::binary | std::ios::in | std::ios::out);
    if (!f) throw InputError(wav.string(), "cannot be opened to repair its header");
    write_u32(f, 4, static_cast<std::uint32_t>(end - 8));
    write_u32(f, layout.data_offset - 4, static_cast<std::uint32_t>(data));
    f.close();
    if (!f) throw InputError(wav.string(), "its header could not be repaired (disk full?)");
}

// Samples at full scale and the peak, for 24-bit mono PCM (what takes are).
void measure_clipping(const std::filesystem::path& wav, const WavLayout& layout,
                      TakeDescription& take) {
    if (layout.format != 1 || layout.bits != 24 || layout.channels != 1) return;
    std::ifstream in(wav, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(layout.data_offset));
    std::string block(3 * 65536, '\0');
    std::uint64_t left = layout.frames;
    int largest = 0;
    while (left > 0 && in) {
        const std::uint64_t n = std::min<std::uint64_t>(left, 65536);
        in.read(block.data(), static_cast<std::streamsize>(3 * n));
        for (std::uint64_t i = 0; i < n; ++i) {
            const auto* p = reinterpret_cast<const unsigned char*>(block.data() + 3 * i);
            std::int32_t v = p[0] | p[1] << 8 | p[2] << 16;
            if (v & 0x800000) v -= 0x1000000;
            if (v >= 0x7FFFFF || v <= -0x800000) ++take.clipped_samples;
            largest = std::max(largest, v < 0 ? -v : v);
        }
        left -= n;
    }
    take.peak = largest / static_cast<double>(0x7FFFFF);
}

// Ends probes.csv after its last whole row.
void trim_probes(const std::filesystem::path& csv) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(csv, ec);
    if (ec || size == 0) return;
    std::ifstream in(csv, std::ios::binary);
    const std::uint64_t tail = std::min<std::uint64_t>(size, 1 << 16);
    std::string last(tail, '\0');
    in.seekg(static_cast<std::streamoff>(size - tail));
    in.read(last.data(), static_cast<std::streamsize>(tail));
    if (!in || last.back() == '\n') return;
    const auto newline = last.rfind('\n');
    if (newline != std::string::npos)
        std::filesystem::resize_file(csv, size - tail + newline + 1, ec);
}

}  // namespace

WavLayout parse_wav_layout(std::string_view head, std::uint64_t file_size,
                           const std::string& source) {
    if (head.size() < 12 || head.substr(0, 4) != "RIFF" || head.substr(8, 4) != "WAVE")
        throw InputError(source, "is not a WAV file (no RIFF/WAVE header)");
    WavLayout w;
    bool have_format = false;
    for (std::size_t at = 12; at + 8 <= head.size();) {
        const std::string_view id = head.substr(at, 4);
        const std::uint32_t size = u32(head, at + 4);
        if (id == "data") {
            if (!have_format) throw InputError(source, "has its data before its format chunk");
            w.data_offset = at + 8;
            if (w.data_offset > file_size) break;
            w.header_frames = size / w.block_align;
            w.frames = (file_size - w.data_offset) / w.block_align;
            // A WAV counts its bytes in 32 bits: what lies beyond cannot be said.
            const std::uint64_t most =
                (std::numeric_limits<std::uint32_t>::max() - w.data_offset) / w.block_align;
            w.frames = std::min(w.frames, most);
            return w;
        }
        if (id == "fmt ") {
            if (size < 16 || at + 8 + size > head.size())
                throw InputError(source, "has a format chunk cut short");
            w.format = u16(head, at + 8);
            w.channels = u16(head, at + 10);
            w.block_align = u16(head, at + 20);
            w.bits = u16(head, at + 22);
            if (w.format == 0xFFFE && size >= 40) w.format = u16(head, at + 32);
            if (w.channels == 0 || w.block_align == 0 || w.bits == 0)
                throw InputError(source, "has a format chunk with no channel or no sample size");
            have_format = true;
        }
        const std::uint64_t next = at + 8 + static_cast<std::uint64_t>(size) + (size & 1);
        if (next > head.size()) break;
        at = static_cast<std::size_t>(next);
    }
    throw InputError(source, "has no data chunk where its samples should begin");
}

std::string format_gesture_line(const GestureKeyframe& k) {
    return Json::array({k.time, k.slide, k.press}).dump() + "\n";
}

std::vector<GestureKeyframe> parse_gesture_stream(std::string_view text,
                                                  const std::string& source) {
    std::vector<GestureKeyframe> keyframes;
    for_each_line(text, source, [&](const Json& line, const std::string& where) {
        if (line.size() != 3) throw InputError(where, "must be [time, slide, press]");
        const GestureKeyframe k{finite(line[0], where, "time"), finite(line[1], where, "slide"),
                                finite(line[2], where, "press")};
        if (!keyframes.empty() && !(k.time > keyframes.back().time))
            throw InputError(where, "its time must come after the line before's");
        keyframes.push_back(k);
    });
    return keyframes;
}

std::string format_parameter_line(const ParameterChange& c) {
    Json line = Json::array({c.tick, c.parameter, c.value, c.glide_samples});
    if (c.from) line.push_back(*c.from), line.push_back(c.done);  // a glide under way
    return line.dump() + "\n";
}

std::vector<ParameterChange> parse_parameter_stream(std::string_view text,
                                                    const std::string& source) {
    std::vector<ParameterChange> changes;
    for_each_line(text, source, [&](const Json& line, const std::string& where) {
        if ((line.size() != 4 && line.size() != 6) || !line[0].is_number_unsigned() ||
            !line[1].is_string() || !line[3].is_number_integer() ||
            (line.size() == 6 && !line[5].is_number_integer()))
            throw InputError(where,
                             "must be [tick, \"ELEMENT.PARAMETER\", value, glide_samples] "
                             "(and from, done for a glide under way)");
        ParameterChange c;
        c.tick = line[0].get<std::uint64_t>();
        c.parameter = line[1].get<std::string>();
        c.value = finite(line[2], where, "value");
        const auto glide = line[3].get<std::int64_t>();
        if (glide < 1 || glide > std::numeric_limits<int>::max())
            throw InputError(where, "glide_samples must be at least 1");
        c.glide_samples = static_cast<int>(glide);
        if (line.size() == 6) {
            c.from = finite(line[4], where, "from");
            const auto done = line[5].get<std::int64_t>();
            c.done = done < 0 || done > c.glide_samples ? -1 : static_cast<int>(done);
            check_in_flight(c, where);
        }
        if (!changes.empty() && c.tick < changes.back().tick)
            throw InputError(where, "changes must be in the order they were made");
        changes.push_back(std::move(c));
    });
    return changes;
}

TakeFolderLock::TakeFolderLock(const std::filesystem::path& folder) {
    fd_ = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    held_ = fd_ >= 0 && ::flock(fd_, LOCK_EX | LOCK_NB) == 0;
}

TakeFolderLock::~TakeFolderLock() {
    if (fd_ >= 0) ::close(fd_);  // releases the lock
}

RecoveredTake recover_take(const std::filesystem::path& folder) {
    TakeFolderLock lock(folder);
    if (!lock.held())
        throw InputError(folder.string(),
                         "is being recorded right now; stop the take, then render it");
    RecoveredTake r;
    r.take = read_take_file(folder / "take.json");
    r.header_frames = r.take.frames;
    if (r.take.complete) return r;
    // Recovery rewrites and truncates the take's files in place: never through a symbolic link
    // (a take folder from elsewhere could point gesture.json at a file of the user's).
    for (const char* name : {"take.wav", "probes.csv", "gesture.json", "gesture.jsonl",
                             "parameters.json", "parameters.jsonl", "take.json", "state.bin"})
        if (std::filesystem::is_symlink(folder / name))
            throw InputError((folder / name).string(),
                             "is a symbolic link; Archet recovers only the files it recorded "
                             "itself, so replace the link with the take's own file");

    const std::filesystem::path wav = folder / "take.wav";
    std::error_code ec;
    const std::uint64_t size = std::filesystem::file_size(wav, ec);
    if (ec)
        throw InputError(wav.string(), "cannot be read (" + ec.message() +
                                           "): nothing of the take can be recovered");
    std::string head(std::min<std::uint64_t>(size, 1 << 16), '\0');
    {
        std::ifstream in(wav, std::ios::binary);
        in.read(head.data(), static_cast<std::streamsize>(head.size()));
        if (!in) throw InputError(wav.string(), "cannot be read");
    }
    const WavLayout layout = parse_wav_layout(head, size, wav.string());
    if (layout.frames == 0)
        throw InputError(wav.string(), "holds no sample: the take stopped before it recorded one");
    const std::filesystem::path gesture_stream = folder / "gesture.jsonl";
    const auto keyframes =
        parse_gesture_stream(read_text_file(gesture_stream), gesture_stream.string());
    if (keyframes.empty())
        throw InputError(gesture_stream.string(), "holds no keyframe; the take cannot be replayed");
    const std::filesystem::path parameter_stream = folder / "parameters.jsonl";
    std::vector<ParameterChange> changes;
    if (std::filesystem::exists(parameter_stream))
        changes =
            parse_parameter_stream(read_text_file(parameter_stream), parameter_stream.string());

    repair_wav(wav, layout, size);
    trim_probes(folder / "probes.csv");
    r.header_frames = layout.header_frames;
    r.take.frames = layout.frames;
    measure_clipping(wav, layout, r.take);
    write_file_atomically(folder / "gesture.json", format_gesture(Gesture("take", keyframes)));
    r.take.has_parameters = !changes.empty();
    if (r.take.has_parameters)
        write_file_atomically(folder / "parameters.json", format_parameter_changes(changes));
    r.take.complete = true;
    r.take.interrupted = true;
    r.take.interrupted_by = "its recorder was killed or crashed before it could finish the take";
    write_file_atomically(folder / "take.json", format_take(r.take));  // the take is whole
    std::filesystem::remove(gesture_stream, ec);
    std::filesystem::remove(parameter_stream, ec);
    // What an atomic write cut short left.
    for (const auto& e : std::filesystem::directory_iterator(folder, ec))
        if (e.path().filename().string().find(".tmp-") != std::string::npos)
            std::filesystem::remove(e.path(), ec);
    return r;
}

}  // namespace archet
