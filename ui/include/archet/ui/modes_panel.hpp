#pragma once
// The model's modes from modal analysis (exact for the scheme): frequency, decay, and each
// partial against the harmonic series in cents, in a table and a plot. The analysis runs off
// the GUI thread: on a 220-mass string it takes about half a second, on a 578-mass one seven,
// at every edit that changes the sounding part; after an edit of the bow, the hand or the
// gesture it classes the modes it has again (ModalAnalysisCache), in milliseconds.

#include <QWidget>

#include <cstddef>

#include "archet/analysis/modal_analysis_cache.hpp"
#include "archet/ui/background_job.hpp"

class QCustomPlot;
class QLabel;
class QTableWidget;

namespace archet {
struct ModalAnalysis;
}

namespace archet::ui {

class ModelDocument;

class ModesPanel : public QWidget {
    Q_OBJECT

  public:
    /// The cents chart shows at least ±5 cents: finer deviations the ear does not hear.
    static constexpr double kCentsSpan = 10;

    explicit ModesPanel(ModelDocument& document, QWidget* parent = nullptr);
    int mode_count() const;
    double fundamental() const { return fundamental_; }
    /// Whether an analysis is under way (the table shows the previous model's until it ends).
    bool computing() const { return job_.busy(); }
    /// How many eigenvalue solves it has made (after an edit that left the sounding part as it
    /// was, it classes the modes of the last one again).
    std::size_t solves_made() const { return analyses_.solves(); }

  private:
    void refresh();
    void show_modes(const ModalAnalysis& modes);
    void show_failure(const QString& message);

    ModelDocument& document_;
    QLabel* summary_;
    QTableWidget* table_;
    QCustomPlot* cents_;
    double fundamental_ = 0;
    bool stale_ = false;           ///< the model changed while the analysis ran: run it again
    ModalAnalysisCache analyses_;  ///< read by the job's worker
    BackgroundJob job_;            ///< last: it joins its worker before the rest goes
};

}  // namespace archet::ui
