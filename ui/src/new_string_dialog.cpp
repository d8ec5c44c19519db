#include "archet/ui/new_string_dialog.hpp"

#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QSpinBox>

namespace archet::ui {

NewStringDialog::NewStringDialog(QWidget* parent) : QDialog(parent) {
    setWindowTitle(tr("New bowed string"));
    const BowedStringOptions defaults;
    pitch_ = new QDoubleSpinBox;
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
    masses_ = new QSpinBox;
    masses_->setRange(24, 60);  // 24 stands for "the largest stable count" (its special text)
    masses_->setSpecialValueText(tr("largest stable"));
    masses_->setValue(24);
    bow_position_ = new QDoubleSpinBox;
    bow_position_->setRange(0.02, 0.48);
    bow_position_->setSingleStep(0.01);
    bow_position_->setDecimals(3);
    bow_position_->setValue(defaults.bow_position);
    bow_position_->setToolTip(tr("β: distance of the bow from the bridge over the string length"));
    t60_ = new QDoubleSpinBox;
    t60_->setRange(0.05, 60);
    t60_->setSuffix(tr(" s"));
    t60_->setValue(defaults.string_t60);
    t60_->setToolTip(tr("How long the first mode takes to decay by 60 dB from string damping"));

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

    auto* form = new QFormLayout(this);
    form->addRow(tr("Pitch (first mode)"), pitch_);
    form->addRow(tr("Tuning"), tuning_);
    form->addRow(tr("Structure"), structure_);
    form->addRow(tr("Masses (25–60)"), masses_);
    form->addRow(tr("Bow position β"), bow_position_);
    form->addRow(tr("String decay T60"), t60_);
    form->addRow(tr("String damping"), damping_);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    form->addRow(buttons);
}

BowedStringOptions NewStringDialog::options() const {
    BowedStringOptions o;
    o.pitch = pitch_->value();
    o.tuning = static_cast<Tuning>(tuning_->currentData().toInt());
    o.structure = static_cast<Structure>(structure_->currentData().toInt());
    o.masses = masses_->value() == masses_->minimum() ? 0 : masses_->value();
    o.bow_position = bow_position_->value();
    o.string_t60 = t60_->value();
    if (damping_->value() > 0) o.string_damping = damping_->value();
    return o;
}

}  // namespace archet::ui
