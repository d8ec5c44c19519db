#include "archet/ui/sweep_form.hpp"

#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QSpinBox>

#include "archet/ui/background_job.hpp"

namespace archet::ui {

QDoubleSpinBox* number_box(double lo, double hi, double value, int decimals,
                           const QString& suffix) {
    auto* box = new QDoubleSpinBox;
    box->setRange(lo, hi);
    box->setDecimals(decimals);
    box->setValue(value);
    box->setSuffix(suffix);
    return box;
}

QSpinBox* count_box(int lo, int hi, int value) {
    auto* box = new QSpinBox;
    box->setRange(lo, hi);
    box->setValue(value);
    return box;
}

QHBoxLayout* range_row(QWidget* lo, QWidget* hi, QWidget* steps) {
    auto* h = new QHBoxLayout;
    h->addWidget(lo), h->addWidget(new QLabel("…")), h->addWidget(hi);
    h->addWidget(new QLabel(QObject::tr("in"))), h->addWidget(steps);
    return h;
}

SweepButtons sweep_buttons(BackgroundJob& job, QWidget* owner) {
    SweepButtons b{new QPushButton(QObject::tr("Compute")), new QPushButton(QObject::tr("Cancel")),
                   new QProgressBar, new QHBoxLayout};
    b.cancel->setEnabled(false);
    b.row->addWidget(b.compute), b.row->addWidget(b.cancel), b.row->addWidget(b.progress, 1);
    QObject::connect(&job, &BackgroundJob::progressed, owner,
                     [bar = b.progress](std::size_t done, std::size_t total) {
                         bar->setMaximum(static_cast<int>(total));
                         bar->setValue(static_cast<int>(done));
                     });
    return b;
}

QString model_changed_text() {
    return QObject::tr(
        "The model has changed since this map was computed: Compute maps it as it "
        "is now. Until then a click plays the map's own model.");
}

}  // namespace archet::ui
