#include "archet/ui/new_string_dialog.hpp"

#include <QCheckBox>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QLabel>
#include <QSpinBox>

#include "archet/builders/string_body.hpp"
#include "archet/builders/string_chain.hpp"

namespace archet::ui {

NewStringDialog::NewStringDialog(QWidget* parent) : QDialog(parent) {
    setWindowTitle(tr("New bowed string"));
    const BowedStringOptions defaults;
    pitch_ = new QDoubleSpinBox;
    pitch_->setObjectName("pitch");
    pitch_->setRange(20, 4000);
    pitch_->setDecimals(2);
    pitch_->setSuffix(tr(" Hz"));
    pitch_->setValue(defaults.pitch);
    tuning_ = new QComboBox;
    tuning_->addItem(tr("Homogeneous (equal masses, flat partials)"),
                     static_cast<int>(Tuning::Homogeneous));
    tuning_->addItem(tr("Harmonic (partials on k·f0)"), static_cast<int>(Tuning::Harmonic));
    structure_ = new QComboBox;
    structure_->addItem(tr("Chain of masses and links"), static_cast<int>(Structure::Chain));
    structure_->addItem(tr("Modal (one oscillator per mode)"), static_cast<int>(Structure::Modal));
    paper_ = new QCheckBox(tr("The paper's chaplet (25–60 masses, link damping, no body)"));
    masses_ = new QSpinBox;
    masses_->setRange(3, 20000);  // 3 stands for "as many as the scheme allows" (special text)
    masses_->setSpecialValueText(tr("full bandwidth"));
    masses_->setValue(3);
    masses_->setToolTip(
        tr("Full bandwidth: as many masses as the scheme allows at the pitch "
           "(with the paper's chaplet: the largest stable count up to 60)"));
    body_ = new QComboBox;
    for (const auto& preset : body_presets())
        body_->addItem(QString::fromStdString(preset.instrument),
                       QString::fromStdString(preset.name));
    body_->addItem(tr("None (heavy damped bridges, sound from the bridge force)"), "none");
    body_->setCurrentIndex(body_->findData(QString::fromStdString(defaults.body)));
    bow_position_ = new QDoubleSpinBox;
    bow_position_->setRange(0.02, 0.48);
    bow_position_->setSingleStep(0.01);
    bow_position_->setDecimals(3);
    bow_position_->setValue(defaults.bow_position);
    bow_position_->setToolTip(tr("β: distance of the bow from the bridge over the string length"));
    finger_ = new QCheckBox(tr("A finger on the string (the pad's keys A W S E … K play it)"));
    finger_->setToolTip(
        tr("A finger pressed at the nut: move it with its position (the sounding share of the "
           "string) in the inspector, or from the pad's keyboard row"));
    connect(structure_, &QComboBox::currentIndexChanged, this, [this] {
        finger_->setEnabled(structure_->currentData().toInt() ==
                            static_cast<int>(Structure::Chain));
    });
    make_material_fields();
    make_loss_fields();
    lay_out();
}

// The string's material: a violin A string's unless changed; the length they give at the pitch
// shows whether that is a string an instrument has.
void NewStringDialog::make_material_fields() {
    const BowedStringOptions defaults;
    tension_ = new QDoubleSpinBox;
    tension_->setObjectName("tension");
    tension_->setRange(1, 2000);
    tension_->setDecimals(1);
    tension_->setSuffix(tr(" N"));
    tension_->setValue(defaults.tension);
    density_ = new QDoubleSpinBox;
    density_->setObjectName("density");
    density_->setRange(0.00001, 0.5);
    density_->setDecimals(6);
    density_->setSingleStep(0.0001);
    density_->setSuffix(tr(" kg/m"));
    density_->setValue(defaults.linear_density);
    const QString material =
        tr("A violin A string's by default (57.1 N, 0.00072 kg/m); a cello's C is about 130 N "
           "and 0.0148 kg/m (--tension and --density on the command line)");
    tension_->setToolTip(material);
    density_->setToolTip(material);
    length_ = new QLabel;
    length_->setObjectName("string_length");
    auto show_length = [this] {
        BowedStringOptions o;
        o.pitch = pitch_->value(), o.tension = tension_->value();
        o.linear_density = density_->value();
        length_->setText(tr("%1 m").arg(string_length(o), 0, 'f', 2));
    };
    for (QDoubleSpinBox* box : {pitch_, tension_, density_})
        connect(box, &QDoubleSpinBox::valueChanged, this, show_length);
    show_length();
}

void NewStringDialog::lay_out() {
    auto* form = new QFormLayout(this);
    form->addRow(tr("Pitch (first mode)"), pitch_);
    form->addRow(tr("Tension"), tension_);
    form->addRow(tr("Linear density"), density_);
    form->addRow(tr("String length"), length_);
    form->addRow(tr("Tuning"), tuning_);
    form->addRow(tr("Structure"), structure_);
    form->addRow(QString(), paper_);
    form->addRow(tr("Masses"), masses_);
    form->addRow(tr("Body"), body_);
    form->addRow(tr("Bow position β"), bow_position_);
    form->addRow(QString(), finger_);
    form->addRow(tr("Decay T60 at the pitch"), t60_);
    form->addRow(tr("Decay T60 high"), t60_high_);
    form->addRow(tr("… at"), t60_high_hz_);
    form->addRow(tr("String damping"), damping_);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    form->addRow(buttons);
}

// Decays (0: a violin A string's own losses), hand-set damping, and what the paper's chaplet
// leaves out.
void NewStringDialog::make_loss_fields() {
    auto decay = [this](const QString& tip) {
        auto* box = new QDoubleSpinBox;
        box->setRange(0, 600);  // 0 stands for the default (its special text)
        box->setDecimals(3);
        box->setSuffix(tr(" s"));
        box->setSpecialValueText(tr("a violin A string's"));
        box->setToolTip(tip);
        return box;
    };
    t60_ = decay(tr("How long the first mode takes to decay by 60 dB, every loss included"));
    t60_high_ = decay(tr("How long the partial near the frequency below takes to decay by 60 dB"));
    t60_high_hz_ = new QDoubleSpinBox;
    t60_high_hz_->setRange(0, 20000);
    t60_high_hz_->setSuffix(tr(" Hz"));
    t60_high_hz_->setSpecialValueText(tr("2000 Hz"));

    damping_ = new QDoubleSpinBox;
    damping_->setRange(0, 10);
    damping_->setDecimals(5);
    damping_->setSingleStep(0.0005);
    damping_->setSuffix(tr(" N·s/m"));
    damping_->setSpecialValueText(tr("from the decay"));
    damping_->setValue(0);
    damping_->setToolTip(
        tr("Damping of each string link; leave at \"from the decay\" to set it "
           "from T60"));
    connect(damping_, &QDoubleSpinBox::valueChanged, this,
            [this](double v) { t60_->setEnabled(v == 0); });
    // The paper's strings have link damping alone (one decay) and no body.
    connect(paper_, &QCheckBox::toggled, this, [this](bool paper) {
        body_->setEnabled(!paper);
        t60_high_->setEnabled(!paper);
        t60_high_hz_->setEnabled(!paper);
        masses_->setSpecialValueText(paper ? tr("largest stable") : tr("full bandwidth"));
    });
}

BowedStringOptions NewStringDialog::options() const {
    BowedStringOptions o;
    o.pitch = pitch_->value();
    o.tension = tension_->value();
    o.linear_density = density_->value();
    o.tuning = static_cast<Tuning>(tuning_->currentData().toInt());
    o.structure = static_cast<Structure>(structure_->currentData().toInt());
    o.paper = paper_->isChecked();
    o.masses = masses_->value() == masses_->minimum() ? 0 : masses_->value();
    o.body = body_->currentData().toString().toStdString();
    o.bow_position = bow_position_->value();
    o.bow_position_fixed = o.bow_position != BowedStringOptions{}.bow_position;
    o.finger = finger_->isEnabled() && finger_->isChecked();
    o.string_t60 = t60_->value();
    o.string_t60_high = t60_high_->value();
    o.string_t60_high_hz = t60_high_hz_->value();
    if (damping_->value() > 0) o.string_damping = damping_->value();
    return o;
}

}  // namespace archet::ui
