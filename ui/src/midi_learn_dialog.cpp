#include "archet/ui/midi_learn_dialog.hpp"

#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QTableWidget>
#include <QVBoxLayout>
#include <algorithm>
#include <limits>

#include "archet/files/model_file.hpp"
#include "archet/model/model_parameters.hpp"

namespace archet::ui {

namespace {

using midi::MidiTarget;

// What a target's range starts as: the default map's where it has one.
struct TargetChoice {
    MidiTarget target;
    const char* label;
    double minimum, maximum;
};
constexpr TargetChoice kPlayerTargets[] = {
    {MidiTarget::BowForce, "Bow force (N)", 0.0, 0.5},
    {MidiTarget::BowSpeed, "Bow speed (m/s)", 0.0, 0.4},
    {MidiTarget::VibratoDepth, "Vibrato depth (semitones)", 0.0, 0.5},
    {MidiTarget::VibratoRate, "Vibrato rate (Hz)", 3.0, 8.0},
    {MidiTarget::FingerPressure, "Finger pressure (0 … 1)", 0.0, 1.0},
    {MidiTarget::BowPosition, "Bow position (β from the bridge)", 0.05, 0.3},
};

bool is_string_element(const std::string& id) {  // s12, k40: too many to list one by one
    return id.size() > 1 && (id[0] == 's' || id[0] == 'k') &&
           std::all_of(id.begin() + 1, id.end(), [](char c) { return c >= '0' && c <= '9'; });
}

QString controller_name(int controller) {
    return controller == midi::kChannelPressure ? QObject::tr("pressure")
                                                : QObject::tr("CC %1").arg(controller);
}

}  // namespace

MidiLearnDialog::MidiLearnDialog(midi::MidiMapping mapping, const Model& model, QWidget* parent)
    : QDialog(parent), mapping_(std::move(mapping)), model_(model) {
    setWindowTitle(tr("MIDI learn"));
    table_ = new QTableWidget(0, 3);
    table_->setObjectName("routes");
    table_->setHorizontalHeaderLabels({tr("Controller"), tr("Moves"), tr("From … to")});
    table_->horizontalHeader()->setStretchLastSection(true);
    table_->setSelectionBehavior(QAbstractItemView::SelectRows);
    table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    auto* remove = new QPushButton(tr("Remove"));
    connect(remove, &QPushButton::clicked, this, &MidiLearnDialog::remove_selected);

    // What a controller can move: the player's targets, then the run-time parameters of the
    // model's elements other than the string's own masses and links.
    target_ = new QComboBox;
    target_->setObjectName("target");
    for (const auto& t : kPlayerTargets)
        if (t.target != MidiTarget::FingerPressure || first_finger(model_))
            target_->addItem(tr(t.label), static_cast<int>(t.target));
    auto add_parameters = [&](const std::string& id) {
        if (is_string_element(id)) return;
        for (const ParameterInfo& p : element_parameters(model_, id)) {
            const ParameterName name{id, p.name};
            const ParameterRole role = parameter_role(model_, name);
            if (role == ParameterRole::Position || role == ParameterRole::Velocity) continue;
            target_->addItem(QString::fromStdString(name.text()),
                             static_cast<int>(MidiTarget::Parameter));
        }
    };
    for (const auto& l : model_.lias) add_parameters(l.id);
    for (const auto& m : model_.mats) add_parameters(m.id);
    minimum_ = new QDoubleSpinBox, maximum_ = new QDoubleSpinBox;
    for (auto* box : {minimum_, maximum_}) {
        box->setDecimals(4);
        box->setRange(-1e9, 1e9);
    }
    connect(target_, &QComboBox::currentIndexChanged, this, &MidiLearnDialog::choose_target);
    heard_label_ = new QLabel(tr("Move a controller on your keyboard…"));
    heard_label_->setObjectName("heard");
    assign_ = new QPushButton(tr("Assign"));
    assign_->setEnabled(false);
    connect(assign_, &QPushButton::clicked, this, &MidiLearnDialog::assign);
    problem_ = new QLabel;
    problem_->setObjectName("problem");
    problem_->setWordWrap(true);
    problem_->setStyleSheet("color: #b00020");

    auto* learn = new QFormLayout;
    learn->addRow(tr("Move"), target_);
    learn->addRow(tr("From (controller at 0)"), minimum_);
    learn->addRow(tr("To (controller at 127)"), maximum_);
    learn->addRow(tr("Controller"), heard_label_);
    learn->addRow(assign_);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Save | QDialogButtonBox::Cancel);
    connect(buttons, &QDialogButtonBox::accepted, this, &MidiLearnDialog::save);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(table_);
    layout->addWidget(remove);
    layout->addLayout(learn);
    layout->addWidget(problem_);
    layout->addWidget(buttons);
    fill_table();
    choose_target();
}

void MidiLearnDialog::fill_table() {
    table_->setRowCount(0);
    for (const auto& r : mapping_.controls) {
        const int row = table_->rowCount();
        table_->insertRow(row);
        QString what = QString::fromStdString(r.parameter.text());
        for (const auto& t : kPlayerTargets)
            if (t.target == r.target) what = tr(t.label);
        table_->setItem(row, 0, new QTableWidgetItem(controller_name(r.controller)));
        table_->setItem(row, 1, new QTableWidgetItem(what));
        table_->setItem(row, 2,
                        new QTableWidgetItem(QString("%1 … %2").arg(r.minimum).arg(r.maximum)));
    }
}

// A new target's range: the player's default, or the parameter's value now up to its table's
// maximum (at most ten times it), which the player narrows.
void MidiLearnDialog::choose_target() {
    const auto target = static_cast<MidiTarget>(target_->currentData().toInt());
    for (const auto& t : kPlayerTargets)
        if (t.target == target) minimum_->setValue(t.minimum), maximum_->setValue(t.maximum);
    if (target != MidiTarget::Parameter) return;
    const ParameterName name = ParameterName::parse(target_->currentText().toStdString());
    const ParameterInfo info = parameter_info(model_, name);
    const double now = get_parameter(model_, name);
    minimum_->setValue(std::max(info.minimum, 0.5 * now));
    maximum_->setValue(std::min(info.maximum, now > 0 ? 1.5 * now : info.maximum));
}

void MidiLearnDialog::heard(int controller, const QString& said) {
    heard_ = controller;
    heard_label_->setText(said.isEmpty() ? controller_name(controller) : said);
    assign_->setEnabled(true);
}

void MidiLearnDialog::assign() {
    if (heard_ < 0) return;
    midi::ControlRoute route;
    route.controller = heard_;
    route.target = static_cast<MidiTarget>(target_->currentData().toInt());
    if (route.target == MidiTarget::Parameter)
        route.parameter = ParameterName::parse(target_->currentText().toStdString());
    route.minimum = minimum_->value(), route.maximum = maximum_->value();
    if (route.target == MidiTarget::Parameter) {
        // Values the engine would refuse are said now, not at every move of the controller.
        const ParameterInfo info = parameter_info(model_, route.parameter);
        for (double v : {route.minimum, route.maximum})
            if (const std::string why = range_problem(info, v); !why.empty()) {
                problem_->setText(QString::fromStdString(route.parameter.text() + ": " + why));
                return;
            }
    }
    std::erase_if(mapping_.controls,
                  [&](const midi::ControlRoute& r) { return r.controller == heard_; });
    mapping_.controls.push_back(route);
    problem_->clear();
    fill_table();
}

void MidiLearnDialog::remove_selected() {
    const int row = table_->currentRow();
    if (row < 0 || row >= static_cast<int>(mapping_.controls.size())) return;
    mapping_.controls.erase(mapping_.controls.begin() + row);
    fill_table();
}

bool MidiLearnDialog::save_to(const QString& path) {
    try {
        const std::string text = midi::write_midi_mapping(mapping_);
        midi::parse_midi_mapping(text, path.toStdString());  // as the engine will read it
        write_file_atomically(path.toStdString(), text);
    } catch (const std::exception& e) {
        problem_->setText(QString::fromUtf8(e.what()));
        return false;
    }
    saved_ = path;
    return true;
}

void MidiLearnDialog::save() {
    const QString path = QFileDialog::getSaveFileName(this, tr("Save the MIDI map"),
                                                      "midi-map.json", tr("MIDI maps (*.json)"));
    if (!path.isEmpty() && save_to(path)) accept();
}

}  // namespace archet::ui
