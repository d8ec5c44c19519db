#include "archet/take_recorder.hpp"

#include <chrono>

#include "archet/input_error.hpp"
#include "archet/model_file.hpp"
#include "archet/state_file.hpp"

namespace archet {

namespace {
constexpr std::uint32_t kSampleCapacity = 1u << 17;  // 2.7 s of samples at 48 kHz
constexpr std::uint32_t kGestureCapacity = 1u << 13;
constexpr std::uint32_t kChangeCapacity = 1u << 10;
// Samples written per round at most: a writer slower than the real-time thread (a loaded
// machine, a sanitizer) still writes the WAV and updates its header every round, instead of
// draining a ring that never empties.
constexpr std::size_t kWriteChunk = 4800;
}  // namespace

TakeRecorder::TakeRecorder(std::filesystem::path folder, const Model& played, double sample_rate,
                           std::vector<std::string> probe_names, std::size_t state_size)
    : folder_(std::move(folder)),
      sample_rate_(sample_rate),
      probe_names_(std::move(probe_names)),
      samples_(kSampleCapacity),
      gestures_(kGestureCapacity),
      changes_(kChangeCapacity),
      state_(state_size) {
    std::error_code ec;
    if (std::filesystem::exists(folder_) && !std::filesystem::is_empty(folder_, ec))
        throw InputError(folder_.string(),
                         "already holds files; a take goes into a new or empty folder");
    std::filesystem::create_directories(folder_, ec);
    if (ec) throw InputError(folder_.string(), "cannot create the take folder: " + ec.message());
    if (probe_names_.size() > ipc::kMaxProbes) probe_names_.resize(ipc::kMaxProbes);
    // The instrument as it plays: at the device's rate, without a gesture of its own.
    Model model = played;
    model.sample_rate = sample_rate_;
    model.gesture.reset();
    write_file_atomically(folder_ / "model.json", format_model(model));
    // Files are opened before playing starts, so that a bad folder fails now, not mid-take.
    wav_ = std::make_unique<SoundFileWriter>(folder_ / "take.wav", SoundFormat::Wav,
                                             static_cast<int>(sample_rate_), WriteMode::Direct);
    csv_ = std::make_unique<ProbeCsvWriter>(folder_ / "probes.csv", probe_names_);
    writer_ = std::thread([this] { write_loop(); });
}

TakeRecorder::~TakeRecorder() {
    try {
        finish();
    } catch (...) {
    }
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
    Sample s;
    s.time = time;
    s.output = output;
    s.count = static_cast<std::uint32_t>(std::min(count, ipc::kMaxProbes));
    for (std::uint32_t i = 0; i < s.count; ++i) s.probes[i] = probes[i];
    samples_.ring().try_push(s);
}

void TakeRecorder::gesture(double time, GestureSample p) {
    gestures_.ring().try_push({time, p.slide, p.press});
}

void TakeRecorder::parameter(std::uint64_t tick, std::uint32_t name, double value,
                             int glide_samples) {
    changes_.ring().try_push({tick, name, glide_samples, value});
}

std::uint64_t TakeRecorder::dropped() const {
    return samples_.ring().dropped() + gestures_.ring().dropped() + changes_.ring().dropped();
}

void TakeRecorder::write_loop() {
    try {
        SoundFileWriter& wav = *wav_;
        ProbeCsvWriter& csv = *csv_;
        std::vector<GestureKeyframe> keyframes;
        std::vector<Change> changes;
        std::vector<double> block;
        auto last_header = std::chrono::steady_clock::now();
        for (;;) {
            const bool last_round = stopping_.load();
            Sample s;
            block.clear();
            while (block.size() < kWriteChunk && samples_.ring().try_pop(s)) {
                block.push_back(s.output);
                csv.write_row(s.time, s.probes);
            }
            const bool more = block.size() == kWriteChunk;  // the ring may hold more
            if (!block.empty()) wav.write(block.data(), block.size());
            frames_.fetch_add(block.size());
            GestureKeyframe k;
            while (gestures_.ring().try_pop(k)) keyframes.push_back(k);
            Change c;
            while (changes_.ring().try_pop(c)) changes.push_back(c);
            if (std::chrono::steady_clock::now() - last_header > std::chrono::seconds(1)) {
                wav.update_header();  // a crash from here on still leaves a valid WAV
                last_header = std::chrono::steady_clock::now();
            }
            if (more) continue;  // at once, without waiting (and not done while it holds more)
            if (last_round) break;
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        wav.close();
        csv.close();
        write_description(std::move(keyframes), changes);
    } catch (const std::exception& e) {
        error_ = e.what();
    }
}

void TakeRecorder::write_description(std::vector<GestureKeyframe> keyframes,
                                     const std::vector<Change>& changes) {
    write_file_atomically(folder_ / "gesture.json",
                          format_gesture(Gesture("take", std::move(keyframes))));
    TakeDescription take;
    take.sample_rate = sample_rate_;
    take.frames = frames_.load();
    const bool begun = begun_.load(std::memory_order_acquire);
    take.start_tick = begun ? start_tick_.load(std::memory_order_relaxed) : 0;
    take.has_state = begun && !state_.empty();
    if (take.has_state) write_state_file(folder_ / "state.bin", state_);
    take.has_parameters = !changes.empty();
    if (take.has_parameters) {
        std::vector<ParameterChange> named;
        const std::lock_guard lock(names_mutex_);
        for (const auto& c : changes)
            named.push_back({c.tick, names_.at(c.name), c.value, c.glide_samples});
        write_file_atomically(folder_ / "parameters.json", format_parameter_changes(named));
    }
    write_file_atomically(folder_ / "take.json", format_take(take));
}

void TakeRecorder::finish() {
    if (finished_) return;
    finished_ = true;
    stopping_.store(true);
    if (writer_.joinable()) writer_.join();
    if (!error_.empty())
        throw InputError(folder_.string(), "the take could not be written: " + error_);
}

}  // namespace archet
