#include "archet/ui/compare_view.hpp"

#include <QComboBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QVBoxLayout>
#include <sstream>

#include "archet/builders/bowed_string.hpp"
#include "archet/common/parallel_for.hpp"
#include "archet/model/model_parameters.hpp"
#include "archet/model/model_variants.hpp"
#include "archet/ui/compare_figure.hpp"

namespace archet::ui {

namespace {
// The current damping of the string and a tenth of it: the paper's Fig. 5 comparison.
QString default_values(const Model& model) {
    const auto links = string_links(model);
    const double damping = links.empty() ? 0.001 : model.find_lia(links.front())->damping;
    return QString("%1, %2").arg(damping / 10, 0, 'g', 3).arg(damping, 0, 'g', 3);
}
// What a failed variant threw, in words.
QString what_it_said(const std::exception_ptr& error) {
    try {
        std::rethrow_exception(error);
    } catch (const std::exception& e) {
        return QString::fromUtf8(e.what());
    } catch (...) {
        return QObject::tr("a variant failed");
    }
}

}  // namespace

CompareView::CompareView(const Model& model, QWidget* parent) : QDialog(parent), model_(model) {
    setWindowTitle(tr("Compare settings — %1").arg(QString::fromStdString(model.name)));
    gesture_ = model_.gesture ? *model_.gesture : steady_bow_gesture();
    parameter_ = new QComboBox;
    parameter_->setEditable(true);
    parameter_->addItem("string.damping");
    parameter_->addItem("bow.position");
    for (const auto& l : model_.lias)
        if (l.kind == LiaKind::BowFriction)
            for (const auto& p : element_parameters(model_, l.id))
                parameter_->addItem(QString::fromStdString(ParameterName{l.id, p.name}.text()));
    parameter_->setToolTip(
        tr("string.damping (N·s/m per string link), bow.position (β), or any "
           "ELEMENT.PARAM"));
    values_ = new QLineEdit(default_values(model_));
    values_->setToolTip(tr("Two or more values, separated by commas"));
    render_ = new QPushButton(tr("Render"));
    cancel_ = new QPushButton(tr("Cancel"));
    cancel_->setEnabled(false);
    progress_ = new QProgressBar;
    progress_->setRange(0, 1);
    progress_->setValue(0);
    message_ = new QLabel(tr("The model's gesture (%1 s) is played on each value, offline.")
                              .arg(gesture_.duration(), 0, 'f', 2));
    message_->setWordWrap(true);
    figure_ = new CompareFigure;
    auto* export_button = new QPushButton(tr("Export figure…"));
    listen_ = new QHBoxLayout;
    listen_->addWidget(new QLabel(tr("Listen:")));
    listen_->addStretch(1);
    listen_->addWidget(export_button);

    auto* form = new QFormLayout;
    form->addRow(tr("Parameter"), parameter_);
    form->addRow(tr("Values"), values_);
    auto* buttons = new QHBoxLayout;
    buttons->addWidget(render_);
    buttons->addWidget(cancel_);
    buttons->addWidget(progress_, 1);
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(form);
    layout->addLayout(buttons);
    layout->addWidget(message_);
    layout->addWidget(figure_, 1);
    layout->addLayout(listen_);
    connect(render_, &QPushButton::clicked, this, &CompareView::render);
    connect(cancel_, &QPushButton::clicked, &job_, &BackgroundJob::cancel);
    connect(&job_, &BackgroundJob::progressed, this,
            [this](std::size_t done) { progress_->setValue(static_cast<int>(done)); });
    connect(export_button, &QPushButton::clicked, this, &CompareView::export_figure);
    connect(parameter_, &QComboBox::currentTextChanged, this, [this](const QString& p) {
        if (p == "string.damping") values_->setText(default_values(model_));
        if (p == "bow.position") values_->setText("0.08, 0.12, 0.2");
    });
    resize(1200, 800);
}

void CompareView::set_variation(const QString& parameter, const QString& values) {
    parameter_->setCurrentText(parameter);
    values_->setText(values);
}

void CompareView::render() {
    if (busy()) return;
    std::pair<std::string, std::vector<double>> variation;
    try {
        QString values = values_->text();
        values.remove(' ');
        variation = parse_variation((parameter_->currentText() + "=" + values).toStdString());
        for (double v : variation.second) {  // every value checked before the work starts
            Model check = model_;
            set_variant_parameter(check, variation.first, v);
        }
    } catch (const std::exception& e) {
        message_->setText(QString::fromUtf8(e.what()));
        return;
    }
    render_->setEnabled(false);
    cancel_->setEnabled(true);
    progress_->setRange(0, static_cast<int>(variation.second.size()));
    progress_->setValue(0);
    message_->setText(tr("rendering…"));
    struct Rendered {
        std::vector<ComparisonRun> runs;
        QString stopped;  ///< why it stopped before the last variant (cancelled, an error)
    };
    job_.start(
        [model = model_, gesture = gesture_, variation](BackgroundJob::Control& control) {
            // On every core, a variant each; those before a failure are still shown.
            ComparedVariants compared = compare_variants(
                model, gesture, variation.first, variation.second, gesture.duration(),
                hardware_jobs(), &control.cancel_flag(),
                [&control](std::size_t done, std::size_t total) { control.progress(done, total); });
            Rendered rendered{std::move(compared.runs), {}};
            if (compared.cancelled) rendered.stopped = tr("cancelled");
            if (compared.error) rendered.stopped = what_it_said(compared.error);
            return rendered;
        },
        [this](Rendered r) { finish(std::move(r.runs), r.stopped); },
        [this](const QString& error) { finish({}, error); });
}

void CompareView::finish(std::vector<ComparisonRun> runs, QString error) {
    render_->setEnabled(true);
    cancel_->setEnabled(false);
    if (!error.isEmpty()) {
        message_->setText(error);
        if (runs.empty()) return;
    }
    runs_ = std::move(runs);
    figure_->show_runs(runs_);
    show_listen_buttons();
    if (error.isEmpty())
        message_->setText(tr("%1 variants rendered; the string's energy lost per period is in each "
                             "title")
                              .arg(runs_.size()));
    emit rendered();
}

// One button per variant: play A, then B, and hear the difference.
void CompareView::show_listen_buttons() {
    while (listen_->count() > 3) {
        QLayoutItem* item = listen_->takeAt(1);
        delete item->widget();
        delete item;
    }
    for (std::size_t i = 0; i < runs_.size(); ++i) {
        auto* play = new QPushButton(QString::fromStdString(runs_[i].label));
        connect(play, &QPushButton::clicked, this, [this, i] {
            player_.play(runs_[i].audio, runs_[i].sample_rate);
            message_->setText(tr("playing %1 on %2")
                                  .arg(QString::fromStdString(runs_[i].label),
                                       QString::fromStdString(player_.description())));
        });
        listen_->insertWidget(static_cast<int>(i) + 1, play);
    }
}

void CompareView::export_figure() {
    const QString path = QFileDialog::getSaveFileName(this, tr("Export the figure"),
                                                      "comparison.png", tr("Images (*.png *.pdf)"));
    if (!path.isEmpty() && !figure_->save(path))
        message_->setText(tr("could not write %1").arg(path));
}

}  // namespace archet::ui
