#pragma once
// The studio's side of the real-time engine, on the GUI thread: starts `archet engine` on a
// fresh shared segment, sends it the model, transport, parameters and the pad's gesture, and
// at display rate keeps its heartbeat, drains what it streams (status, probe frames, string
// shapes) and watches it. An engine that exits or stops answering is restarted with the same
// model, playing again if it was: the user loses nothing.

#include <QObject>
#include <QString>
#include <QTemporaryDir>
#include <QTimer>
#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "archet/link/engine_link.hpp"
#include "archet/model/model.hpp"
#include "archet/model/parameter_name.hpp"
#include "archet/ui/probe_history.hpp"

namespace archet::ui {

struct EngineClientOptions {
    QString archet_binary;  ///< the `archet` executable (beside the studio's)
    QString audio = "auto";
    int audio_device = -1;  ///< a device index of that API (see archet devices); −1: its default
    int buffer_frames = 128;
    /// sim: the pad moves a simulated hand (mass and damping) that holds the bow, so the
    /// mouse's coarse steps reach the string smoothly; or a joystick (evdev:PATH, sdl:N).
    QString haptic = "sim";
    double sample_rate = 48000;  ///< Hz asked of the device; the engine says what it got
    int poll_ms = 15;            ///< display rate
    /// The take folder: the engine is started with it and records takes only inside it.
    QString takes;
    /// The UDP port the engine listens for OSC on, on this machine (0: none).
    int osc_port = 0;
    /// MIDI in: "" (none), "virtual" (the engine's own port archet-midi:midi_in) or a part of a
    /// source's name; its API (alsa, jack); the mapping file (empty: STK's Bowed's controllers).
    QString midi;
    QString midi_api = "alsa";
    QString midi_map;
};

struct EngineStatus {
    QString state = "stopped";  ///< starting, running, unresponsive, restarting
    QString device;             ///< what the engine said about its audio and scheduling
    QString model;              ///< the model it plays
    std::uint64_t xruns = 0, dropped = 0, realtime_allocations = 0;
    double load = 0;         ///< share of the real-time budget used lately (1: all of it)
    double worst_load = 0;   ///< the longest block so far, as a fraction of a block's period
    double sample_rate = 0;  ///< Hz the engine runs at (0 until it says)
    double energy = 0;       ///< J stored in the string
    int restarts = 0;
    QString last_restart;  ///< why and when the engine was last restarted, in words
};

class EngineClient : public QObject {
    Q_OBJECT

  public:
    explicit EngineClient(EngineClientOptions options, QObject* parent = nullptr);
    ~EngineClient() override;

    void start();
    /// Restarts the engine with other options (audio, buffer, device), same model and state.
    void reconfigure(EngineClientOptions options);
    const EngineClientOptions& options() const { return options_; }
    /// Plays `model` (written to the session folder, then loaded by the engine).
    void load(const Model& model);
    /// The model the engine plays, with the parameters set since it was loaded.
    const std::optional<Model>& model() const { return model_; }
    /// The file the engine loads the model from (rewritten per load, not per parameter).
    QString session_model_path() const { return session_.filePath("model.json"); }
    void play();
    void stop();
    bool playing() const { return playing_; }
    /// Glides a parameter of the playing model to `value` (already validated by the caller;
    /// the engine checks it again). Remembered for a restarted engine, without a copy of the
    /// model or a file written per edit.
    void send_parameter(const ParameterName& name, double value);
    void gesture(double slide, double press);
    /// Where takes go: an engine running with another take folder is restarted with this one
    /// (same model and state), since it records only inside the folder it was started with.
    void set_takes_folder(const QString& folder);
    /// Records into `folder`, which must lie inside the take folder.
    void start_take(const QString& folder);
    void stop_take();

    const ProbeHistory& history() const { return history_; }
    /// The string's drawn points, and where each lies along it (its index among the string's
    /// points, from the bridge: a string longer than ipc::kMaxShapePoints is drawn from points
    /// spread along it).
    const std::vector<float>& shape() const { return shape_; }
    const std::vector<double>& shape_along() const { return shape_along_; }
    const EngineStatus& status() const { return status_; }
    pid_t engine_pid() const { return link_ ? link_->engine_pid() : -1; }

  signals:
    void status_changed();
    void message(const QString& text);  ///< errors and take news, for the status bar
    void engine_lost(const QString& why);
    void model_loaded(const QString& name);
    /// A MIDI controller moved (128: channel pressure); `said` describes it.
    void midi_controller(int controller, const QString& said);

  private:
    void poll();
    void launch();
    void restart(const QString& why);
    void read_status();
    void write_session_model();
    void take_back_refused_parameter(std::uint32_t sequence);

    struct SentParameter {
        std::uint32_t sequence;
        ParameterName name;
        double before;  ///< the value the engine plays if it refuses this one
    };
    std::deque<SentParameter> sent_parameters_;
    EngineClientOptions options_;
    std::unique_ptr<link::EngineLink> link_;
    QTimer timer_;
    QTemporaryDir session_;
    std::optional<Model> model_;
    bool playing_ = false;
    double slide_ = 0, press_ = 0;
    ProbeHistory history_;
    std::vector<float> shape_;
    std::vector<double> shape_along_;
    EngineStatus status_;
    std::chrono::steady_clock::time_point unresponsive_since_{};
};

}  // namespace archet::ui
