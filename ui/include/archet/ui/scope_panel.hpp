#pragma once
// The scopes on the string while it plays (QCustomPlot): at the bowing point, its
// displacement, the bow force and its velocity against the bow's (the paper's Fig. 4); the
// bow force against the displacement (Fig. 5, XY); the whole string's shape; and the sound's
// spectrum. Run or freeze, trigger on the slip, a time base, and a cursor with readouts.
// Refreshed at display rate from the probe history; it never touches the audio path.

#include <QWidget>
#include <vector>

#include "archet/ui/probe_history.hpp"

class QCustomPlot;
class QCPCurve;
class QCPItemTracer;
class QCheckBox;
class QComboBox;
class QLabel;

namespace archet::ui {

class ScopePanel : public QWidget {
    Q_OBJECT

  public:
    enum class Scope { Displacement, Force, Velocity, ForceAgainstDisplacement, Shape, Spectrum };

    // The least span an axis shows, in its unit: below it, what moves is numerical noise.
    static constexpr double kDisplacementSpanMm = 0.01;
    static constexpr double kForceSpanN = 1e-3;
    static constexpr double kVelocitySpanMPerS = 1e-3;
    static constexpr double kShapeSpanMm = 0.1;  // the whole string at rest reads as a line
    // The spectrum's window resolves partials this close (Hz) at any sample rate: the lowest
    // shipped string's are 110 Hz apart, and Hann's main lobe is four bins wide.
    static constexpr double kSpectrumResolutionHz = 6;

    explicit ScopePanel(QWidget* parent = nullptr);

    /// `shape` is the string's points as the engine sends them (string_points(): the bow
    /// and any mass not joined to the string are not in it), `along` where each lies along the
    /// string (EngineClient::shape_along()).
    void refresh(const ProbeHistory& history, const std::vector<float>& shape,
                 const std::vector<double>& along, double sample_rate);
    void set_frozen(bool frozen);
    bool frozen() const;
    void set_trigger_on_slip(bool on);
    void set_time_base_ms(double ms);

    /// Samples drawn in the last refresh (0 while nothing arrives).
    int drawn_samples() const { return drawn_; }
    QCustomPlot& plot(Scope scope) const;
    /// Samples in the spectrum's window at `sample_rate`: a power of two, for the FFT.
    static std::size_t spectrum_window(double sample_rate);

  private:
    void show_cursor(double time_ms);
    std::size_t trigger_back(const ProbeHistory& history, std::size_t span) const;
    void refresh_spectrum(const ProbeHistory& history, double sample_rate);

    QCustomPlot* displacement_;
    QCustomPlot* force_;
    QCustomPlot* velocity_;
    QCustomPlot* xy_;
    QCPCurve* xy_curve_;
    QCustomPlot* shape_;
    QCustomPlot* spectrum_;
    QCPItemTracer* tracer_;
    QCheckBox* freeze_;
    QCheckBox* trigger_;
    QComboBox* time_base_;
    QLabel* readout_;
    std::vector<double> times_ms_, x_mm_, force_n_, v_string_, v_bow_;
    int drawn_ = 0;
};

}  // namespace archet::ui
