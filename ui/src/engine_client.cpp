#include "archet/ui/engine_client.hpp"

#include <signal.h>

#include "archet/model_file.hpp"
#include "archet/model_parameters.hpp"

namespace archet::ui {

namespace {
constexpr auto kGiveUpUnresponsive = std::chrono::seconds(2);
}

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
    ipc::EngineLinkOptions o;
    o.archet_binary = options_.archet_binary.toStdString();
    o.audio = options_.audio.toStdString();
    o.block_frames = options_.buffer_frames;
    o.haptic = options_.haptic.toStdString();
    try {
        link_ = std::make_unique<ipc::EngineLink>(o);
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
        link_->load_model(session_.filePath("model.json").toStdString());
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
    status_.state = "restarting";
    status_.model.clear(), status_.device.clear();  // until the new engine says
    ++status_.restarts;
    emit status_changed();
    link_.reset();
    launch();
}

void EngineClient::load(const Model& model) {
    write_file_atomically(session_.filePath("model.json").toStdString(), format_model(model));
    model_ = model;
    if (link_) link_->load_model(session_.filePath("model.json").toStdString());
}

void EngineClient::play() {
    playing_ = true;
    if (link_) link_->play();
}

void EngineClient::stop() {
    playing_ = false;
    if (link_) link_->stop();
}

void EngineClient::set_parameter(const QString& name, double value) {
    if (link_) link_->set_parameter(name.toStdString(), value);
    if (!model_) return;
    // Remembered, so that a restarted engine plays what the user set.
    const auto dot = name.lastIndexOf('.');
    try {
        Model changed = *model_;
        archet::set_parameter(changed, name.left(dot).toStdString(),
                              name.mid(dot + 1).toStdString(), value);
        write_file_atomically(session_.filePath("model.json").toStdString(), format_model(changed));
        model_ = std::move(changed);
    } catch (const std::exception&) {
        // The engine answers with the reason; nothing to remember.
    }
}

void EngineClient::gesture(double slide, double press) {
    slide_ = slide, press_ = press;
    if (link_) link_->gesture(slide, press);
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
    if (fresh)
        shape_.assign(shape.positions,
                      shape.positions + std::min<std::uint32_t>(shape.count, ipc::kMaxShapePoints));
    switch (link_->liveness()) {
        case ipc::EngineLink::Liveness::Exited:
            return restart("the engine exited (status " + QString::number(link_->exit_status()) +
                           "); restarted with the same model");
        case ipc::EngineLink::Liveness::Unresponsive: {
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
        case ipc::EngineLink::Liveness::Running:
            unresponsive_since_ = {};
            if (status_.state != "running") {
                status_.state = "running";
                emit status_changed();
            }
            return;
        case ipc::EngineLink::Liveness::Starting:
            return;
    }
}

void EngineClient::read_status() {
    auto status = link_->status();
    ipc::StatusFrame f;
    bool changed = false;
    while (status.try_pop(f)) {
        const QString text = QString::fromUtf8(f.text);
        status_.xruns = f.xruns, status_.dropped = f.dropped, status_.load = f.load;
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
                history_.reset(names);
                shape_.clear();
                emit model_loaded(text);
                break;
            }
            case ipc::StatusKind::Error:
                emit message("engine: " + text);
                break;
            case ipc::StatusKind::Blowup:
                emit message("engine: " + text);
                break;
            case ipc::StatusKind::Take:
                emit message("take " + text);
                break;
        }
    }
    if (changed) emit status_changed();
}

}  // namespace archet::ui
