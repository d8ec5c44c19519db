#include "archet/ui/inspector.hpp"

#include <QComboBox>
#include <QDoubleValidator>
#include <QFormLayout>
#include <QLabel>
#include <QLineEdit>
#include <QVBoxLayout>

#include "archet/analysis/playability.hpp"
#include "archet/common/number_text.hpp"
#include "archet/model/model_parameters.hpp"
#include "archet/model/stability.hpp"
#include "archet/model/stability_limit.hpp"
#include "archet/ui/model_document.hpp"

namespace archet::ui {

namespace {
// The table's unit and range, as the field's tooltip.
QString range_text(const ParameterInfo& p) {
    const QString unit = p.unit.empty() ? QString() : " " + QString::fromStdString(p.unit);
    return Inspector::tr("%1: %2 %3 to %4%5%6")
        .arg(QString::fromStdString(p.name))
        .arg(p.strictly_positive ? Inspector::tr("above") : Inspector::tr("from"))
        .arg(p.minimum, 0, 'g', 6)
        .arg(p.maximum, 0, 'g', 6)
        .arg(unit)
        .arg(p.stability_relevant ? Inspector::tr("; the stability bound depends on it")
                                  : QString());
}
}  // namespace

Inspector::Inspector(ModelDocument& document, QWidget* parent)
    : QWidget(parent), document_(document) {
    title_ = new QLabel;
    title_->setWordWrap(true);
    stability_ = new QLabel;
    stability_->setWordWrap(true);
    warning_label_ = new QLabel;
    warning_label_->setWordWrap(true);
    warning_label_->setStyleSheet("color: #b03020");
    fields_ = new QWidget;
    form_ = new QFormLayout(fields_);
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(title_);
    layout->addWidget(fields_);
    layout->addWidget(warning_label_);
    layout->addWidget(stability_);
    layout->addStretch(1);
    // Moving nodes changes no parameter: the stability limits (many eigenvalue problems)
    // are not worth redoing at every step of a drag.
    connect(&document_, &ModelDocument::changed, this, [this](ModelDocument::Change change) {
        if (change != ModelDocument::Change::Layout) rebuild();
    });
    rebuild();
}

void Inspector::show_element(const QString& id) {
    element_ = id;
    warning_.clear();
    warning_label_->clear();
    rebuild();
}

bool Inspector::edit(const QString& parameter, double value) {
    // The document checks it once: the table's range, then stability.
    return apply([&] {
        document_.edit_parameter({element_.toStdString(), parameter.toStdString()}, value);
    });
}

bool Inspector::move_bow(double beta) {
    return apply([&] { document_.move_bow(beta); });
}

bool Inspector::apply(const std::function<void()>& change) {
    warning_.clear();
    warning_label_->clear();
    try {
        change();
    } catch (const std::exception& e) {
        warning_ = tr("Not applied: %1").arg(QString::fromUtf8(e.what()));
        warning_label_->setText(warning_);
        rebuild();  // the field shows the value still in force
        return false;
    }
    return true;
}

// A field for a number, typed in the C locale; `typed` gets it when typing ends.
QLineEdit* Inspector::number_field(const QString& name, const QString& text,
                                   const std::function<void(double)>& typed) {
    auto* field = new QLineEdit(text);
    field->setObjectName(name);
    auto* validator = new QDoubleValidator(field);
    validator->setLocale(QLocale::c());
    field->setValidator(validator);
    connect(field, &QLineEdit::editingFinished, this, [field, typed] {
        bool ok = false;
        const double value = QLocale::c().toDouble(field->text(), &ok);
        if (ok) typed(value);
    });
    return field;
}

// β on the bow's module, its contact point and its own mass, for a bowed chain of masses
// s1…sN or of points there in modal form (bow_position() is 0 for any other model).
void Inspector::add_bow_position(const std::string& id) {
    const Model& model = document_.model();
    const Lia* bow = first_bow(model);
    if (!bow || (id != bow->id && id != bow->bowed_string() && id != bow->bow())) return;
    const double beta = bow_position(model);
    if (beta <= 0) return;
    QLineEdit* field =
        number_field("bow.position", QString::number(beta, 'g', 6), [this, beta](double value) {
            if (value != beta) move_bow(value);
        });
    field->setToolTip(
        tr("bow.position: where the bow meets the string, from the bridge over the "
           "string's length, above 0 to below 0.5; the bow moves to the nearest "
           "string mass and a playing string goes on"));
    form_->addRow(tr("bow position β"), field);
}

void Inspector::rebuild() {
    while (form_->rowCount() > 0) form_->removeRow(0);
    const Model& model = document_.model();
    const std::string id = element_.toStdString();
    const Mat* mat = model.find_mat(id);
    const Lia* lia = model.find_lia(id);
    if (!mat && !lia) {
        element_.clear();
        title_->setText(
            tr("<b>%1</b><br>%2, %3. Select an element to edit it.")
                .arg(QString::fromStdString(model.name),
                     QString::fromStdString(
                         count_of(model.mats.size(), "mass or point", "masses and points")),
                     QString::fromStdString(count_of(model.lias.size(), "link", "links"))));
        show_stability();
        return;
    }
    const QString kind = mat ? to_string(mat->kind) : to_string(lia->kind);
    const std::string& rate = mat ? mat->rate : lia->rate;
    title_->setText(tr("<b>%1</b> — %2").arg(element_, kind));
    auto* rates = new QComboBox;
    for (const auto& r : model.rates)
        rates->addItem(tr("%1 (÷%2)").arg(QString::fromStdString(r.id)).arg(r.divider),
                       QString::fromStdString(r.id));
    rates->setCurrentIndex(rates->findData(QString::fromStdString(rate)));
    connect(rates, &QComboBox::activated, this, [this, rates] {
        try {
            document_.set_rate(element_, rates->currentData().toString());
        } catch (const std::exception& e) {
            warning_label_->setText(QString::fromUtf8(e.what()));
        }
    });
    form_->addRow(tr("Rate level"), rates);
    for (const ParameterInfo& p : element_parameters(model, id)) {
        const QString name = QString::fromStdString(p.name);
        QLineEdit* field =
            number_field(name, QString::number(get_parameter(model, {id, p.name}), 'g', 10),
                         [this, name](double value) {
                             const double now = get_parameter(
                                 document_.model(), {element_.toStdString(), name.toStdString()});
                             if (value != now) edit(name, value);
                         });
        field->setToolTip(range_text(p));
        const QString unit = QString::fromStdString(p.unit);
        form_->addRow(unit.isEmpty() ? name : tr("%1 (%2)").arg(name, unit), field);
        // This element's own margin: how far the value may go before the scheme turns unstable.
        if (const auto limit =
                p.stability_relevant ? document_.stability_limit({id, p.name}) : std::nullopt) {
            const double room = limit->upper ? 1 - limit->current / limit->value
                                             : 1 - limit->value / limit->current;
            auto* margin = new QLabel(tr("%1 %2 %3 to stay stable (%4 % of room left)")
                                          .arg(limit->upper ? tr("below") : tr("above"))
                                          .arg(limit->value, 0, 'g', 4)
                                          .arg(unit)
                                          .arg(100 * room, 0, 'f', 1));
            margin->setStyleSheet(room < 0.1 ? "color: #b03020" : "color: gray");
            margin->setWordWrap(true);  // the side panel is narrower than the sentence
            form_->addRow(margin);      // the width of both columns: fewer lines
        }
    }
    add_bow_position(id);
    show_stability();
}

void Inspector::show_stability() {
    try {
        QStringList lines;
        for (const StabilityReport& r : analyse_stability(document_.model()))
            if (!r.stiffest_dof.empty())  // a level with no moving mass cannot go unstable
                lines << tr("rate %1: %2 % of the stability bound left (stiffest: %3)")
                             .arg(QString::fromStdString(r.rate))
                             .arg(100 * r.margin(), 0, 'f', 1)
                             .arg(QString::fromStdString(r.stiffest_dof));
        stability_->setText(lines.join("<br>"));
    } catch (const std::exception& e) {
        stability_->setText(QString::fromUtf8(e.what()));
    }
}

}  // namespace archet::ui
