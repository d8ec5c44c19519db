#include "archet/ui/modes_panel.hpp"

#include <qcustomplot.h>

#include <QHeaderView>
#include <QLabel>
#include <QTableWidget>
#include <QVBoxLayout>
#include <cmath>

#include "archet/analysis/modal_analysis.hpp"
#include "archet/common/number_text.hpp"
#include "archet/ui/model_document.hpp"
#include "archet/ui/plot_palette.hpp"
#include "archet/ui/scope_axis.hpp"

namespace archet::ui {

namespace {
// A frequency as one reads it: "220.0 Hz", one decimal (a tenth of a hertz is a cent at 170 Hz).
QString hertz(double frequency) {
    return QObject::tr("%1 Hz").arg(frequency, 0, 'f', 1);
}

// Signed, to a tenth of a cent: "+0.0", "-15.5"; -0.0 reads as +0.0.
QString cents_text(double cents) {
    const double shown = std::round(cents * 10) / 10;
    return (shown < 0 ? QString() : QStringLiteral("+")) + QString::number(shown + 0.0, 'f', 1);
}
}  // namespace

ModesPanel::ModesPanel(ModelDocument& document, QWidget* parent)
    : QWidget(parent), document_(document) {
    summary_ = new QLabel;
    summary_->setWordWrap(true);
    table_ = new QTableWidget(0, 5);
    table_->setHorizontalHeaderLabels(
        {tr("mode"), tr("frequency"), tr("partial"), tr("cents"), tr("T60 s")});
    table_->verticalHeader()->setVisible(false);
    table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    // Each column as wide as what it shows (a narrow panel scrolls rather than cutting
    // "220.0 Hz" to "22…"); the last takes what is left.
    table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
    table_->horizontalHeader()->setStretchLastSection(true);
    cents_ = new QCustomPlot;
    cents_->setMinimumHeight(220);  // room for its axis label and five ticks
    cents_->xAxis->setLabel(tr("partial"));
    cents_->yAxis->setLabel(tr("cents from k·f1"));
    auto* bars = new QCPBars(cents_->xAxis, cents_->yAxis);
    bars->setBrush(QColor(60, 110, 200, 160));
    follow_palette(*cents_);
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(summary_);
    layout->addWidget(cents_, 1);
    layout->addWidget(table_, 2);
    connect(&document_, &ModelDocument::changed, this, [this](ModelDocument::Change change) {
        if (change != ModelDocument::Change::Layout) refresh();
    });
    connect(&job_, &BackgroundJob::finished, this, [this] {
        if (stale_) stale_ = false, refresh();
    });
    refresh();
}

int ModesPanel::mode_count() const {
    return table_->rowCount();
}

// One analysis at a time, on a copy of the model; edits made meanwhile start the next.
void ModesPanel::refresh() {
    if (job_.busy()) {
        stale_ = true;
        return;
    }
    job_.start([model = document_.model(),
                &analyses = analyses_](BackgroundJob::Control&) { return analyses.of(model); },
               [this](const ModalAnalysis& modes) { show_modes(modes); },
               [this](const QString& message) { show_failure(message); });
}

void ModesPanel::show_failure(const QString& message) {
    table_->setRowCount(0);
    static_cast<QCPBars*>(cents_->plottable(0))->data()->clear();
    fundamental_ = 0;
    summary_->setText(tr("No modes: %1").arg(message));
    cents_->replot();
}

void ModesPanel::show_modes(const ModalAnalysis& modes) {
    table_->setRowCount(0);
    auto* bars = static_cast<QCPBars*>(cents_->plottable(0));
    bars->data()->clear();
    fundamental_ = modes.fundamental;
    summary_->setText(
        tr("%1 at rate %2; f1 = %3")
            .arg(QString::fromStdString(count_of(modes.modes.size(), "mode", "modes")),
                 QString::fromStdString(modes.rate), hertz(modes.fundamental)));
    QVector<double> partials, cents;
    table_->setRowCount(static_cast<int>(modes.modes.size()));
    int row = 0;
    for (std::size_t i = 0; i < modes.modes.size(); ++i, ++row) {
        const ModeInfo& m = modes.modes[i];
        auto cell = [&](int column, const QString& text) {
            table_->setItem(row, column, new QTableWidgetItem(text));
        };
        cell(0, QString::number(i + 1));
        cell(1, hertz(m.frequency));
        cell(2, m.support ? tr("support") : QString::number(m.partial));
        cell(3, m.support ? QString() : cents_text(m.cents));
        cell(4, std::isfinite(m.t60) ? QString::number(m.t60, 'g', 4) : tr("∞"));
        if (!m.support) partials << m.partial, cents << m.cents;
    }
    bars->setData(partials, cents);
    // The bars stand on 0, so 0 is in view; a harmonic string's round-off stays flat.
    double lowest = 0, highest = 0;
    for (double c : cents) lowest = std::min(lowest, c), highest = std::max(highest, c);
    fit_axis(*cents_->yAxis, lowest, highest, kCentsSpan);
    cents_->xAxis->setRange(0, std::max(2.0, partials.isEmpty() ? 2.0 : partials.back() + 1));
    cents_->replot();
}

}  // namespace archet::ui
