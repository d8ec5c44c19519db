#include "archet/ui/scope_panel.hpp"

#include <qcustomplot.h>

#include <QCheckBox>
#include <QComboBox>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <unsupported/Eigen/FFT>

#include "archet/ui/plot_palette.hpp"
#include "archet/ui/scope_axis.hpp"

namespace archet::ui {

namespace {

QCustomPlot* make_plot(const QString& title, const QString& x_label, const QString& y_label) {
    auto* plot = new QCustomPlot;
    plot->setMinimumSize(220, 120);
    plot->plotLayout()->insertRow(0);
    auto* heading = new QCPTextElement(plot, title, QFont(plot->font().family(), 9, QFont::Bold));
    plot->plotLayout()->addElement(0, 0, heading);
    plot->xAxis->setLabel(x_label);
    plot->yAxis->setLabel(y_label);
    plot->addGraph();
    plot->graph(0)->setPen(QPen(QColor(30, 90, 180), 1.4));
    plot->setNotAntialiasedElements(QCP::aeAll);  // cheap to redraw at display rate
    return plot;
}

QVector<double> to_vector(const std::vector<double>& v) {
    return QVector<double>(v.begin(), v.end());
}

}  // namespace

ScopePanel::ScopePanel(QWidget* parent) : QWidget(parent) {
    displacement_ = make_plot(tr("Displacement at the bowing point"), tr("ms"), tr("mm"));
    force_ = make_plot(tr("Bow force (friction on the string)"), tr("ms"), tr("N"));
    velocity_ = make_plot(tr("Velocity at the bowing point"), tr("ms"), tr("m/s"));
    velocity_->addGraph();
    velocity_->graph(1)->setPen(QPen(QColor(200, 80, 40), 1.2, Qt::DashLine));
    velocity_->graph(0)->setName(tr("string"));
    velocity_->graph(1)->setName(tr("bow"));
    velocity_->legend->setVisible(true);
    velocity_->legend->setFont(QFont(font().family(), 8));

    xy_ = make_plot(tr("Bow force against displacement (Fig. 5)"), tr("displacement (mm)"),
                    tr("force (N)"));
    xy_->removeGraph(0);
    xy_curve_ = new QCPCurve(xy_->xAxis, xy_->yAxis);
    xy_curve_->setPen(QPen(QColor(120, 40, 160), 1.2));
    shape_ = make_plot(tr("The string"), tr("mass"), tr("mm"));
    shape_->graph(0)->setPen(QPen(QColor(150, 110, 40), 2));
    spectrum_ = make_plot(tr("Spectrum of the sound"), tr("Hz"), tr("dB"));
    spectrum_->xAxis->setScaleType(QCPAxis::stLogarithmic);
    spectrum_->xAxis->setTicker(QSharedPointer<QCPAxisTickerLog>(new QCPAxisTickerLog));
    spectrum_->xAxis->setRange(50, 12000);
    spectrum_->yAxis->setRange(-120, 0);

    tracer_ = new QCPItemTracer(velocity_);
    tracer_->setGraph(velocity_->graph(0));
    tracer_->setStyle(QCPItemTracer::tsCrosshair);
    tracer_->setPen(QPen(Qt::gray, 1, Qt::DotLine));
    tracer_->setVisible(false);

    freeze_ = new QCheckBox(tr("Freeze"));
    trigger_ = new QCheckBox(tr("Trigger on slip"));
    trigger_->setChecked(true);
    time_base_ = new QComboBox;
    for (int ms : {5, 10, 20, 50, 100, 200}) time_base_->addItem(tr("%1 ms").arg(ms), ms);
    time_base_->setCurrentIndex(2);
    readout_ = new QLabel(tr("Move the mouse over a trace for readouts"));
    readout_->setTextInteractionFlags(Qt::TextSelectableByMouse);

    auto* controls = new QHBoxLayout;
    controls->addWidget(freeze_);
    controls->addWidget(trigger_);
    controls->addWidget(new QLabel(tr("Time base")));
    controls->addWidget(time_base_);
    controls->addWidget(readout_, 1);

    auto* grid = new QGridLayout;
    grid->addWidget(displacement_, 0, 0);
    grid->addWidget(force_, 1, 0);
    grid->addWidget(velocity_, 2, 0);
    grid->addWidget(xy_, 0, 1);
    grid->addWidget(shape_, 1, 1);
    grid->addWidget(spectrum_, 2, 1);
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(controls);
    layout->addLayout(grid, 1);
    for (QCustomPlot* plot : {displacement_, force_, velocity_, xy_, shape_, spectrum_})
        follow_palette(*plot);

    for (QCustomPlot* plot : {displacement_, force_, velocity_})
        connect(plot, &QCustomPlot::mouseMove, this, [this, plot](QMouseEvent* e) {
            show_cursor(plot->xAxis->pixelToCoord(e->position().x()));
        });
}

void ScopePanel::set_frozen(bool frozen) {
    freeze_->setChecked(frozen);
}

bool ScopePanel::frozen() const {
    return freeze_->isChecked();
}

void ScopePanel::set_trigger_on_slip(bool on) {
    trigger_->setChecked(on);
}

void ScopePanel::set_time_base_ms(double ms) {
    const int i = time_base_->findData(static_cast<int>(ms));
    if (i >= 0) time_base_->setCurrentIndex(i);
}

// How far back the window ends so that it starts where the string begins to slip: the newest
// such onset that leaves a whole window after it.
std::size_t ScopePanel::trigger_back(const ProbeHistory& h, std::size_t span) const {
    const int slip = h.channel("slip_v");
    if (!trigger_->isChecked() || slip < 0) return 0;
    const std::vector<double> s = h.window(slip, 3 * span);
    if (s.size() < 2 * span) return 0;
    // Sticking, the bow and the string move together to round-off (~1e-13 m/s).
    auto slipping = [](double v) { return std::abs(v) > 1e-6; };
    for (std::size_t i = s.size() - span; i-- > 1;)
        if (slipping(s[i]) && !slipping(s[i - 1])) return s.size() - (i + span);
    return 0;
}

void ScopePanel::refresh(const ProbeHistory& h, const std::vector<float>& shape,
                         const std::vector<double>& along, double sample_rate) {
    if (frozen()) return;
    const double time_base = time_base_->currentData().toDouble();
    const auto span = static_cast<std::size_t>(time_base * 1e-3 * sample_rate);
    const std::size_t back = trigger_back(h, span);
    auto read = [&](const char* name, double scale) {
        std::vector<double> v = h.window(h.channel(name), span, back);
        for (double& x : v) x *= scale;
        return v;
    };
    x_mm_ = read("bow_point_x", 1000);
    force_n_ = read("friction_force", 1);
    v_string_ = read("bow_point_v", 1);
    v_bow_ = read("bow_v", 1);
    drawn_ = static_cast<int>(x_mm_.size());
    times_ms_.resize(x_mm_.size());
    for (std::size_t i = 0; i < times_ms_.size(); ++i) times_ms_[i] = 1e3 * i / sample_rate;

    const QVector<double> t = to_vector(times_ms_);
    displacement_->graph(0)->setData(t, to_vector(x_mm_), true);
    force_->graph(0)->setData(t, to_vector(force_n_), true);
    velocity_->graph(0)->setData(t, to_vector(v_string_), true);
    velocity_->graph(1)->setData(t, to_vector(v_bow_), true);
    for (QCustomPlot* plot : {displacement_, force_, velocity_})
        plot->xAxis->setRange(0, time_base);
    fit_axis(*displacement_->yAxis, x_mm_, kDisplacementSpanMm);
    fit_axis(*force_->yAxis, force_n_, kForceSpanN);
    std::vector<double> both = v_string_;
    both.insert(both.end(), v_bow_.begin(), v_bow_.end());
    fit_axis(*velocity_->yAxis, both, kVelocitySpanMPerS);

    xy_curve_->setData(to_vector(x_mm_), to_vector(force_n_));
    fit_axis(*xy_->xAxis, x_mm_, kDisplacementSpanMm);
    fit_axis(*xy_->yAxis, force_n_, kForceSpanN);

    QVector<double> index, position;
    for (std::size_t i = 0; i < shape.size(); ++i)
        index.push_back(i < along.size() ? along[i] : static_cast<double>(i)),
            position.push_back(1000.0 * shape[i]);
    shape_->graph(0)->setData(index, position, true);
    shape_->xAxis->setRange(0, std::max(1.0, index.isEmpty() ? 0.0 : index.back()));
    fit_axis(*shape_->yAxis, std::vector<double>(position.begin(), position.end()), kShapeSpanMm);

    refresh_spectrum(h, sample_rate);
    for (QCustomPlot* plot : {displacement_, force_, velocity_, xy_, shape_, spectrum_})
        plot->replot(QCustomPlot::rpQueuedReplot);
}

QCustomPlot& ScopePanel::plot(Scope scope) const {
    switch (scope) {
        case Scope::Displacement:
            return *displacement_;
        case Scope::Force:
            return *force_;
        case Scope::Velocity:
            return *velocity_;
        case Scope::ForceAgainstDisplacement:
            return *xy_;
        case Scope::Shape:
            return *shape_;
        case Scope::Spectrum:
            break;
    }
    return *spectrum_;
}

std::size_t ScopePanel::spectrum_window(double sample_rate) {
    constexpr std::size_t kLongest = std::size_t{1} << 16;  // 1.4 s at 48 kHz
    std::size_t n = 1024;
    while (n < kLongest && sample_rate / static_cast<double>(n) > kSpectrumResolutionHz) n *= 2;
    return n;
}

// The sound's spectrum over the newest window, Hann-windowed; its axis says the resolution
// that window gives, or how much sound it still waits for, in two lines: one is wider than the
// plot in the studio's window.
void ScopePanel::refresh_spectrum(const ProbeHistory& h, double sample_rate) {
    const std::size_t n = spectrum_window(sample_rate);
    const double seconds = static_cast<double>(n) / sample_rate;
    const std::vector<double> sound = h.window(ProbeHistory::kOutput, n);
    if (sound.size() < n) {
        spectrum_->graph(0)->data()->clear();
        spectrum_->xAxis->setLabel(tr("Hz (waiting for %1 s of sound:\n%2 of %3 samples)")
                                       .arg(seconds, 0, 'f', 2)
                                       .arg(sound.size())
                                       .arg(n));
        return;
    }
    std::vector<double> windowed(n);
    for (std::size_t i = 0; i < n; ++i)
        windowed[i] =
            sound[i] * 0.5 *
            (1 - std::cos(2 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n)));
    Eigen::FFT<double> fft;
    std::vector<std::complex<double>> bins;
    fft.fwd(bins, windowed);
    const double bin_hz = sample_rate / static_cast<double>(n);
    QVector<double> hz, db;
    for (std::size_t k = 1; k < n / 2; ++k) {
        hz.push_back(static_cast<double>(k) * bin_hz);
        db.push_back(20 * std::log10(std::abs(bins[k]) / (static_cast<double>(n) / 4) + 1e-12));
    }
    spectrum_->graph(0)->setData(hz, db, true);
    spectrum_->xAxis->setLabel(tr("Hz (resolution %1 Hz:\n%2-sample Hann window, %3 s)")
                                   .arg(bin_hz, 0, 'f', 1)
                                   .arg(n)
                                   .arg(seconds, 0, 'f', 2));
}

void ScopePanel::show_cursor(double time_ms) {
    if (times_ms_.empty()) return;
    const double step = times_ms_.size() > 1 ? times_ms_[1] : 1;
    const auto i = static_cast<std::size_t>(
        std::clamp(std::lround(time_ms / step), 0L, static_cast<long>(times_ms_.size() - 1)));
    tracer_->setVisible(true);
    tracer_->setGraphKey(times_ms_[i]);
    readout_->setText(tr("t %1 ms   displacement %2 mm   force %3 N   velocity %4 m/s (bow %5)")
                          .arg(times_ms_[i], 0, 'f', 3)
                          .arg(x_mm_[i], 0, 'f', 4)
                          .arg(force_n_[i], 0, 'f', 4)
                          .arg(v_string_[i], 0, 'f', 4)
                          .arg(v_bow_[i], 0, 'f', 4));
    velocity_->replot(QCustomPlot::rpQueuedReplot);
}

}  // namespace archet::ui
