#include "archet/ui/engine_client.hpp"

#include <signal.h>

#include <QTime>
#include <algorithm>

#include "archet/common/input_error.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/model_parameters.hpp"
#include "archet/model/string_points.hpp"

namespace archet::ui {

namespace {
constexpr auto kGiveUpUnresponsive = std::chrono::seconds(2);
constexpr double kHistorySeconds = 4;              // what the scopes and spectrum may look back on
constexpr std::size_t kRememberedParameters = 64;  // sent, not yet known to be refused
}  // namespace

EngineClient::EngineClient(EngineClientOptions options, QObject* parent)
    : QObject(parent), options_(std::move(options)) {
    connect(&timer_, &QTimer::timeout, this, &EngineClient::poll);
}

EngineClient::~EngineClient() = default;  // the link asks the engine to quit, then kills it

void EngineClient::start() {
    launch();
    timer_.start(options_.poll_ms);
}

void EngineClient::launch() {
    link::EngineLinkOptions o;
    o.archet_binary = options_.archet_binary.toStdString();
    o.audio = options_.audio.toStdString();
    o.audio_device = options_.audio_device;
    o.block_frames = options_.buffer_frames;
    o.haptic = options_.haptic.toStdString();
    o.osc_port = options_.osc_port;
    o.midi = options_.midi.toStdString();
    o.midi_api = options_.midi_api.toStdString();
    o.midi_map = options_.midi_map.toStdString();
    o.sample_rate = options_.sample_rate;
    o.takes = options_.takes.toStdString();
    try {
        link_ = std::make_unique<link::EngineLink>(o);
        link_->start();
    } catch (const std::exception& e) {  // no engine binary, no shared memory: say so, stay up
        link_.reset();
        status_.state = "not running";
        emit message(tr("cannot start the engine (%1): %2")
                         .arg(options_.archet_binary, QString::fromUtf8(e.what())));
        emit status_changed();
        return;
    }
    status_.state = "starting";
    unresponsive_since_ = {};
    if (model_) {  // a restart: the same model, playing again if it was
        try {
            write_session_model();           // with the parameters set since it was loaded
        } catch (const std::exception& e) {  // the last file written still holds the model
            emit message(tr("could not write the session's model (%1); the engine restarts "
                            "with the model as last loaded")
                             .arg(QString::fromUtf8(e.what())));
        }
        link_->load_model(session_model_path().toStdString());
        if (playing_) link_->play();
        link_->gesture(slide_, press_);
    }
    emit status_changed();
}

void EngineClient::reconfigure(EngineClientOptions options) {
    options_ = std::move(options);
    status_.model.clear(), status_.device.clear();
    link_.reset();
    launch();
}

void EngineClient::restart(const QString& why) {
    emit engine_lost(why);
    status_.last_restart = tr("%1 at %2").arg(why, QTime::currentTime().toString("HH:mm:ss"));
    status_.state = "restarting";
    status_.model.clear(), status_.device.clear();  // until the new engine says
    ++status_.restarts;
    emit status_changed();
    link_.reset();
    launch();
}

void EngineClient::load(const Model& model) {
    model_ = model;
    sent_parameters_.clear();
    write_session_model();
    if (link_) link_->load_model(session_model_path().toStdString());
}

// The engine reads models from a file: written when it loads one, not at every parameter.
void EngineClient::write_session_model() {
    write_file_atomically(session_model_path().toStdString(), format_model(*model_));
}

void EngineClient::play() {
    playing_ = true;
    if (link_) link_->play();
}

void EngineClient::stop() {
    playing_ = false;
    if (link_) link_->stop();
}

// The document validated the value: it is sent and remembered as it is, not checked again.
void EngineClient::send_parameter(const ParameterName& name, double value) {
    const std::uint32_t sequence = link_ ? link_->send_parameter(name, value) : 0;
    if (!model_) return;
    // Remembered, so that a restarted engine plays what the user set; taken back if the
    // engine refuses it (read_status).
    double* field = nullptr;
    try {
        field = &parameter_field(*model_, name);  // a lookup, no check
    } catch (const InputError&) {
        return;  // not in the model it loaded: the engine refuses it and says why
    }
    if (sequence != 0) {
        sent_parameters_.push_back({sequence, name, *field});
        if (sent_parameters_.size() > kRememberedParameters) sent_parameters_.pop_front();
    }
    *field = value;
}

void EngineClient::gesture(double slide, double press) {
    slide_ = slide, press_ = press;
    if (link_) link_->gesture(slide, press);
}

void EngineClient::set_takes_folder(const QString& folder) {
    if (options_.takes == folder) return;
    EngineClientOptions o = options_;
    o.takes = folder;
    if (link_)
        reconfigure(std::move(o));
    else
        options_ = std::move(o);
}

void EngineClient::start_take(const QString& folder) {
    if (link_) link_->start_take(folder.toStdString());
}

void EngineClient::stop_take() {
    if (link_) link_->stop_take();
}

void EngineClient::poll() {
    if (!link_) return;
    link_->heartbeat();
    read_status();
    auto probes = link_->probes();
    ipc::ProbeFrame frame;
    while (probes.try_pop(frame)) history_.append(frame);
    auto shapes = link_->shapes();
    ipc::ShapeFrame shape;
    bool fresh = false;
    while (shapes.try_pop(shape)) fresh = true;
    if (fresh) {
        const std::uint32_t count = std::min<std::uint32_t>(shape.count, ipc::kMaxShapePoints);
        shape_.assign(shape.positions, shape.positions + count);
        const std::vector<std::size_t> drawn =
            drawn_points(std::max(shape.spread_over, count), ipc::kMaxShapePoints);
        shape_along_.resize(count);
        for (std::uint32_t i = 0; i < count; ++i)
            shape_along_[i] = static_cast<double>(drawn.size() == count ? drawn[i] : i);
    }
    switch (link_->liveness()) {
        case link::EngineLink::Liveness::Exited:
            return restart("the engine exited (status " + QString::number(link_->exit_status()) +
                           "); restarted with the same model");
        case link::EngineLink::Liveness::Unresponsive: {
            const auto now = std::chrono::steady_clock::now();
            if (unresponsive_since_ == std::chrono::steady_clock::time_point{}) {
                unresponsive_since_ = now;
                status_.state = "unresponsive";
                emit status_changed();
            } else if (now - unresponsive_since_ > kGiveUpUnresponsive) {
                ::kill(link_->engine_pid(), SIGKILL);
                return restart("the engine stopped answering; restarted with the same model");
            }
            return;
        }
        case link::EngineLink::Liveness::Running:
            unresponsive_since_ = {};
            if (status_.state != "running") {
                status_.state = "running";
                emit status_changed();
            }
            return;
        case link::EngineLink::Liveness::Starting:
            return;
    }
}

// The engine refused a parameter the studio sent (it checks at the rate it runs at): the
// model kept for a restart goes back to the value the engine still plays.
void EngineClient::take_back_refused_parameter(std::uint32_t sequence) {
    if (sequence == 0) return;  // not an answer to a command of ours (an OSC message's refusal)
    const auto sent = std::find_if(sent_parameters_.begin(), sent_parameters_.end(),
                                   [&](const SentParameter& p) { return p.sequence == sequence; });
    if (sent == sent_parameters_.end() || !model_) return;
    parameter_field(*model_, sent->name) = sent->before;  // it was in force before
    sent_parameters_.erase(sent);
}

void EngineClient::read_status() {
    auto status = link_->status();
    ipc::StatusFrame f;
    bool changed = false;
    while (status.try_pop(f)) {
        const QString text = QString::fromUtf8(f.text);
        status_.xruns = f.xruns, status_.dropped = f.dropped, status_.load = f.load;
        status_.worst_load = f.worst_load;
        // The header holds what the device runs at (written before the engine's first frame).
        status_.sample_rate = link_->sample_rate();
        status_.energy = f.energy, status_.realtime_allocations = f.realtime_allocations;
        changed = true;
        switch (static_cast<ipc::StatusKind>(f.kind)) {
            case ipc::StatusKind::Heartbeat:
                if (status_.device.isEmpty()) status_.device = text;
                break;
            case ipc::StatusKind::ModelLoaded: {
                status_.model = text;
                std::vector<std::string> names;
                if (model_)
                    for (const auto& p : model_->probes) names.push_back(p.id);
                // The same seconds of history at any rate the engine runs at.
                if (status_.sample_rate > 0)
                    history_ = ProbeHistory(
                        static_cast<std::size_t>(kHistorySeconds * status_.sample_rate));
                history_.reset(names);
                shape_.clear(), shape_along_.clear();
                emit model_loaded(text);
                break;
            }
            case ipc::StatusKind::Error:
                take_back_refused_parameter(f.sequence);
                emit message("engine: " + text);
                break;
            case ipc::StatusKind::Blowup:
                emit message("engine: " + text);
                break;
            case ipc::StatusKind::Take:
                emit message("take " + text);
                break;
            case ipc::StatusKind::Midi:
                emit midi_controller(static_cast<int>(f.sequence), text);
                break;
        }
    }
    if (changed) emit status_changed();
}

}  // namespace archet::ui
