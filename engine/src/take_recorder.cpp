#include "archet/engine/take_recorder.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <sstream>

#include "archet/common/input_error.hpp"
#include "archet/common/number_text.hpp"
#include "archet/files/model_file.hpp"
#include "archet/files/state_file.hpp"

namespace archet {

namespace {
constexpr std::uint32_t kSampleCapacity = 1u << 17;  // 2.7 s of samples at 48 kHz
// The most memory the samples waiting for the writer take: at 48 kHz a model with many probes
// waits for less than 2.7 s (a hundred probes 0.68 s, the most a model has, 1,024, 43 ms).
constexpr std::size_t kSampleBytes = std::size_t{1} << 25;
constexpr std::uint32_t kGestureCapacity = 1u << 13;
constexpr std::uint32_t kChangeCapacity = 1u << 10;
// Samples written per round at most: a writer that falls behind still writes take.wav and
// the streams every round instead of draining an ever-refilled ring into probes.csv alone.
constexpr std::size_t kRoundSamples = 1u << 13;

std::FILE* open_stream(const std::filesystem::path& path) {
    std::FILE* f = std::fopen(path.c_str(), "wx");  // new: a take never overwrites a file
    if (!f) throw InputError(path.string(), "cannot be created (is the folder writable?)");
    return f;
}

// Records of a sample: its time, the output, each probe.
std::size_t sample_length(std::size_t probes) {
    return 2 + probes;
}

std::uint32_t sample_capacity(std::size_t probes) {
    const std::size_t fit = kSampleBytes / (sample_length(probes) * sizeof(double));
    return static_cast<std::uint32_t>(
        std::bit_floor(std::clamp<std::size_t>(fit, 1, kSampleCapacity)));
}

void put(std::FILE* f, const std::string& line, const std::filesystem::path& path) {
    if (std::fputs(line.c_str(), f) < 0)
        throw InputError(path.string(), "write failed (disk full?)");
}
}  // namespace

TakeRecorder::TakeRecorder(std::filesystem::path folder, const Model& played, double sample_rate,
                           std::vector<std::string> probe_names, std::size_t state_size)
    : folder_(std::move(folder)),
      sample_rate_(sample_rate),
      probe_names_(std::move(probe_names)),
      samples_(sample_length(probe_names_.size()), sample_capacity(probe_names_.size())),
      gestures_(kGestureCapacity),
      changes_(kChangeCapacity),
      state_(state_size) {
    slot_names_.reserve(kSlotNames);
    std::error_code ec;
    if (std::filesystem::exists(folder_) && !std::filesystem::is_empty(folder_, ec))
        throw InputError(folder_.string(),
                         "already holds files; a take goes into a new or empty folder");
    std::filesystem::create_directories(folder_, ec);
    if (ec) throw InputError(folder_.string(), "cannot create the take folder: " + ec.message());
    lock_ = std::make_unique<TakeFolderLock>(folder_);
    if (!lock_->held())
        throw InputError(folder_.string(),
                         "is being recorded into by another take; choose another");
    // The instrument as it plays: at the device's rate, without a gesture of its own.
    Model model = played;
    model.sample_rate = sample_rate_;
    model.gesture.reset();
    write_file_atomically(folder_ / "model.json", format_model(model));
    // What the take is, from its first moment: a take killed outright is still one.
    TakeDescription take = description();
    take.complete = false;
    write_file_atomically(folder_ / "take.json", format_take(take));
    // Files are opened before playing starts, so that a bad folder fails now, not mid-take.
    wav_ = std::make_unique<SoundFileWriter>(folder_ / "take.wav", SoundFormat::Wav,
                                             static_cast<int>(sample_rate_), WriteMode::Direct);
    csv_ =
        std::make_unique<ProbeCsvWriter>(folder_ / "probes.csv", probe_names_, WriteMode::Direct);
    gesture_stream_ = open_stream(folder_ / "gesture.jsonl");
    writer_ = std::thread([this] { write_loop(); });
}

TakeRecorder::~TakeRecorder() {
    try {
        finish();
    } catch (...) {
    }
    if (gesture_stream_) std::fclose(gesture_stream_);
    if (parameter_stream_) std::fclose(parameter_stream_);
}

std::uint32_t TakeRecorder::parameter_name(const std::string& name) {
    const std::lock_guard lock(names_mutex_);
    for (std::size_t i = 0; i < names_.size(); ++i)
        if (names_[i] == name) return static_cast<std::uint32_t>(i);
    names_.push_back(name);
    return static_cast<std::uint32_t>(names_.size() - 1);
}

void TakeRecorder::begin(std::uint64_t tick) {
    start_tick_.store(tick, std::memory_order_relaxed);
    begun_.store(true, std::memory_order_release);  // publishes the state buffer too
}

void TakeRecorder::sample(double time, double output, const double* probes, std::size_t count) {
    if (blown_up_at_.load(std::memory_order_relaxed) >= 0) return;
    if (!std::isfinite(output)) {
        blown_up_at_.store(time, std::memory_order_relaxed);
        return;
    }
    double* const record = samples_.claim();
    if (!record) return;  // counted as dropped
    record[0] = time;
    record[1] = output;
    const std::size_t columns = probe_names_.size();
    for (std::size_t i = 0; i < columns; ++i) record[2 + i] = i < count ? probes[i] : 0.0;
    samples_.publish();
}

void TakeRecorder::gesture(double time, GestureSample p) {
    gestures_.ring().try_push({time, p.slide, p.press});
}

void TakeRecorder::parameter(std::uint64_t tick, std::uint32_t name, double value,
                             int glide_samples) {
    changes_.ring().try_push({tick, name, glide_samples, value});
}

void TakeRecorder::name_slot(const ParameterSlot& slot, const std::string& name) {
    if (slot_names_.size() < kSlotNames) slot_names_.push_back({slot, parameter_name(name)});
}

void TakeRecorder::name_slot_waiting(const ParameterSlot& slot, std::uint32_t name) {
    for (const auto& [known, _] : slot_names_)  // a fader streams the same slot: named once
        if (known == slot) return;
    if (slot_names_.size() < kSlotNames) slot_names_.push_back({slot, name});  // no allocation
}

void TakeRecorder::glide_under_way(const ParameterSmoother::Glide& g) {
    // A slot has one name (it is one parameter of the model), however often it was named.
    for (const auto& [slot, name] : slot_names_)
        if (slot == g.slot) {
            changes_.ring().try_push({start_tick_.load(std::memory_order_relaxed), name, g.total,
                                      g.to, true, g.from, g.done});
            return;
        }
    unnamed_glides_.fetch_add(1, std::memory_order_relaxed);  // counted as lost: said at the end
}

std::uint64_t TakeRecorder::dropped_samples() const {
    return samples_.dropped();
}

std::uint64_t TakeRecorder::dropped_events() const {
    return gestures_.ring().dropped() + changes_.ring().dropped() + unnamed_glides_.load();
}

TakeDescription TakeRecorder::description() const {
    TakeDescription take;
    take.sample_rate = sample_rate_;
    take.frames = frames_.load();
    const bool begun = begun_.load(std::memory_order_acquire);
    take.start_tick = begun ? start_tick_.load(std::memory_order_relaxed) : 0;
    take.has_state = begun && !state_.empty();
    return take;
}

std::vector<ParameterChange> TakeRecorder::named(const std::vector<Change>& changes) {
    std::vector<ParameterChange> list;
    const std::lock_guard lock(names_mutex_);
    for (const auto& c : changes) {
        list.push_back({c.tick, names_.at(c.name), c.value, c.glide_samples, std::nullopt, 0});
        if (c.under_way) list.back().from = c.from, list.back().done = c.done;
    }
    return list;
}

// Each round: the samples that came, then the gesture and changes that came before them (the
// real-time side pushes those first), which reach the disk first. So whatever take.wav holds
// when the process dies, the streams hold what replays it.
void TakeRecorder::write_loop() {
    try {
        SoundFileWriter& wav = *wav_;
        ProbeCsvWriter& csv = *csv_;
        std::vector<GestureKeyframe> keyframes;
        std::vector<Change> changes;
        std::vector<double> block;
        block.reserve(kRoundSamples);
        bool described = false;
        auto last_header = std::chrono::steady_clock::now();
        for (;;) {
            const bool last_round = stopping_.load();
            block.clear();
            while (block.size() < kRoundSamples) {
                const double* const s = samples_.front();  // time, output, probes
                if (!s) break;
                block.push_back(s[1]);
                csv.write_row(s[0], s + 2);
                samples_.release();
            }
            const bool behind = block.size() == kRoundSamples;
            // Begun before its first sample was pushed: where it began is known now.
            if (!described && begun_.load(std::memory_order_acquire)) {
                described = true;
                const TakeDescription take = description();
                if (take.has_state) write_state_file(folder_ / "state.bin", state_);
                TakeDescription recording = take;
                recording.complete = false;
                write_file_atomically(folder_ / "take.json", format_take(recording));
            }
            GestureKeyframe k;
            bool streamed = false;
            while (gestures_.ring().try_pop(k)) {
                keyframes.push_back(k);
                put(gesture_stream_, format_gesture_line(k), folder_ / "gesture.jsonl");
                streamed = true;
            }
            if (streamed) std::fflush(gesture_stream_);
            Change c;
            const std::size_t known = changes.size();
            while (changes_.ring().try_pop(c)) changes.push_back(c);
            if (changes.size() > known) {
                if (!parameter_stream_)
                    parameter_stream_ = open_stream(folder_ / "parameters.jsonl");
                const std::vector<Change> fresh(
                    changes.begin() + static_cast<std::ptrdiff_t>(known), changes.end());
                for (const auto& change : named(fresh))
                    put(parameter_stream_, format_parameter_line(change),
                        folder_ / "parameters.jsonl");
                std::fflush(parameter_stream_);
            }
            if (!block.empty()) wav.write(block.data(), block.size());
            csv.flush();
            frames_.fetch_add(block.size());
            if (std::chrono::steady_clock::now() - last_header > std::chrono::seconds(1)) {
                wav.update_header();  // a crash from here on still leaves a valid WAV
                last_header = std::chrono::steady_clock::now();
            }
            if (behind) continue;  // more are waiting (the last round too drains them all)
            if (last_round) break;
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        wav.close();
        csv.close();
        clipped_ = wav.clipped_samples();
        peak_ = wav.peak();
        write_description(std::move(keyframes), changes);
    } catch (const std::exception& e) {
        error_ = e.what();
    }
}

void TakeRecorder::write_description(std::vector<GestureKeyframe> keyframes,
                                     const std::vector<Change>& changes) {
    write_file_atomically(folder_ / "gesture.json",
                          format_gesture(Gesture("take", std::move(keyframes))));
    TakeDescription take = description();
    if (take.has_state && !std::filesystem::exists(folder_ / "state.bin"))
        write_state_file(folder_ / "state.bin", state_);
    take.has_parameters = !changes.empty();
    if (take.has_parameters)
        write_file_atomically(folder_ / "parameters.json",
                              format_parameter_changes(named(changes)));
    take.interrupted = !interrupted_by_.empty();
    take.interrupted_by = interrupted_by_;
    take.clipped_samples = clipped_;
    take.peak = peak_;
    take.dropped_samples = dropped_samples();
    take.dropped_events = dropped_events();
    write_file_atomically(folder_ / "take.json", format_take(take));  // whole from here on
    // The streams served a take that might not be finished; this one is.
    std::fclose(gesture_stream_);
    gesture_stream_ = nullptr;
    std::error_code ignored;
    std::filesystem::remove(folder_ / "gesture.jsonl", ignored);
    if (parameter_stream_) {
        std::fclose(parameter_stream_);
        parameter_stream_ = nullptr;
        std::filesystem::remove(folder_ / "parameters.jsonl", ignored);
    }
}

void TakeRecorder::finish(const std::string& interrupted_by) {
    if (finished_) return;
    finished_ = true;
    const double blown_up_at = blown_up_at_.load();
    interrupted_by_ =
        !interrupted_by.empty() ? interrupted_by
        : blown_up_at >= 0
            ? "the simulation stopped being finite at t = " + format_number(blown_up_at) + " s"
            : std::string();  // read by the writer after it sees stopping_
    stopping_.store(true);
    if (writer_.joinable()) writer_.join();
    lock_.reset();
    if (!error_.empty())
        throw InputError(folder_.string(), "the take could not be written: " + error_);
}

std::string TakeRecorder::incomplete_note() const {
    const std::uint64_t samples = dropped_samples(), events = dropped_events();
    if (samples == 0 && events == 0) return {};
    std::ostringstream s;
    s << "the take is incomplete: it lost " << samples << " samples and " << events
      << " gesture positions or parameter changes, which take.json counts";
    if (samples > 0) {
        s << " (its writer fell behind: a slow disk";
        if (!probe_names_.empty())
            s << ", or the " << probe_names_.size() << " probes probes.csv holds at every sample";
        s << ")";
    }
    s << "; take.wav does not hold the whole performance, and `render --take` will not "
         "reproduce it";
    return s.str();
}

std::string TakeRecorder::clipping_note() const {
    if (clipped_ == 0) return {};
    std::ostringstream s;
    s << "the take clipped: " << clipped_ << " of " << frames_.load()
      << " samples at full scale (peak " << peak_
      << "); the live limiter kept what was heard clean, but take.wav holds the model's own "
         "output; "
      << gain_advice(peak_);
    return s.str();
}

}  // namespace archet
