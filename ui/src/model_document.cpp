#include "archet/ui/model_document.hpp"

#include <QUndoCommand>
#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "archet/analysis/playability.hpp"
#include "archet/common/input_error.hpp"
#include "archet/common/number_text.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/model_parameters.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/model/model_variants.hpp"

namespace archet::ui {

namespace {
constexpr int kMoveMerge = 1;  // QUndoCommand::id() of a drag's moves

// The model's rate set to the one it runs at while it is validated, and back afterwards: no
// copy of the model, and the file keeps its own rate.
class RunningRate {
  public:
    RunningRate(Model& model, double hz) : model_(model), own_(model.sample_rate) {
        if (hz > 0) model_.sample_rate = hz;
    }
    ~RunningRate() { model_.sample_rate = own_; }
    RunningRate(const RunningRate&) = delete;
    RunningRate& operator=(const RunningRate&) = delete;

  private:
    Model& model_;
    double own_;
};

QString elements(qsizetype count) {
    return QString::fromStdString(count_of(static_cast<std::size_t>(count), "element", "elements"));
}
}  // namespace

// One edit: the model before and after it.
class ModelEdit : public QUndoCommand {
  public:
    ModelEdit(ModelDocument& document, const QString& text, Model before, Model after,
              ModelDocument::Change change, QString element, QString name, int merge)
        : QUndoCommand(text),
          document_(document),
          before_(std::move(before)),
          after_(std::move(after)),
          change_(change),
          element_(std::move(element)),
          name_(std::move(name)),
          merge_(merge) {}

    void redo() override { document_.apply(after_, change_, element_, name_); }
    void undo() override { document_.apply(before_, change_, element_, name_); }
    int id() const override { return merge_; }
    bool mergeWith(const QUndoCommand* other) override {
        const auto* next = static_cast<const ModelEdit*>(other);
        if (next->merge_ != merge_ || next->element_ != element_) return false;
        after_ = next->after_;
        return true;
    }

  private:
    ModelDocument& document_;
    Model before_, after_;
    ModelDocument::Change change_;
    QString element_, name_;
    int merge_;
};

// One parameter's change: its value before and after, not two copies of the model (a long
// string edited value by value would otherwise copy it twice per keystroke).
class ParameterEdit : public QUndoCommand {
  public:
    ParameterEdit(ModelDocument& document, ParameterName name, double before, double after)
        : QUndoCommand(QObject::tr("Set %1").arg(QString::fromStdString(name.text()))),
          document_(document),
          name_(std::move(name)),
          before_(before),
          after_(after) {}

    void redo() override {
        document_.apply_parameter(
            name_, after_,
            fresh_ ? ModelDocument::Change::Parameter : ModelDocument::Change::ReplayedParameter);
        fresh_ = false;
    }
    void undo() override {
        document_.apply_parameter(name_, before_, ModelDocument::Change::ReplayedParameter);
    }

  private:
    ModelDocument& document_;
    ParameterName name_;
    double before_, after_;
    bool fresh_ = true;  ///< the first redo() is the edit itself, validated when it was made
};

ModelDocument::ModelDocument(QObject* parent) : QObject(parent) {}

void ModelDocument::reset(const Model& model, const QString& path) {
    undo_.clear();
    model_ = model;
    set_path(path);
    emit changed(Change::Structure, {}, {});
    emit replaced();
}

void ModelDocument::set_path(const QString& path) {
    path_ = path;
    emit path_changed(path_);
}

void ModelDocument::apply(const Model& model, Change change, const QString& element,
                          const QString& name) {
    model_ = model;
    emit changed(change, element, name);
}

// Both values were in force in a validated model: written without another check (undo and
// redo are checked against the model as it is now by whoever plays them).
void ModelDocument::apply_parameter(const ParameterName& name, double value, Change change) {
    parameter_field(model_, name) = value;
    emit changed(change, QString::fromStdString(name.element),
                 QString::fromStdString(name.parameter));
}

void ModelDocument::push(const QString& text, Model after, Change change, const QString& element,
                         const QString& name, int merge) {
    undo_.push(new ModelEdit(*this, text, model_, std::move(after), change, element, name, merge));
}

QString ModelDocument::fresh_id(const QString& stem) const {
    for (int n = 1;; ++n) {
        const std::string id = stem.toStdString() + std::to_string(n);
        if (!model_.find_mat(id) && !model_.find_lia(id)) return QString::fromStdString(id);
    }
}

void ModelDocument::validate() {
    const RunningRate at(model_, running_rate_);
    validate_model(model_);
}

std::optional<StabilityLimit> ModelDocument::stability_limit(const ParameterName& name) {
    return archet::stability_limit(model_, name);
}

QPointF ModelDocument::position_of(const Mat& mat) const {
    if (mat.display) return {mat.display->first, mat.display->second};
    // No position yet: a row, in model order.
    const auto index = std::find_if(model_.mats.begin(), model_.mats.end(),
                                    [&](const Mat& m) { return m.id == mat.id; }) -
                       model_.mats.begin();
    return {40.0 * static_cast<double>(index), 0.0};
}

QString ModelDocument::add_mat(MatKind kind, QPointF at, const QString& rate) {
    static const std::map<MatKind, QString> stems{{MatKind::Mass, "m"},
                                                  {MatKind::Fixed, "fixed"},
                                                  {MatKind::Oscillator, "osc"},
                                                  {MatKind::Gesture, "hand"}};
    Mat m;
    m.kind = kind;
    m.id = fresh_id(stems.count(kind) ? stems.at(kind) : "point").toStdString();
    m.rate = rate.toStdString();
    if (kind == MatKind::Mass || kind == MatKind::Oscillator) m.mass = 1e-3;
    if (kind == MatKind::Oscillator) m.stiffness = 100.0, m.damping = 0.1;
    m.display = std::make_pair(at.x(), at.y());
    Model after = model_;
    after.mats.push_back(m);
    push(tr("Add %1").arg(QString::fromStdString(m.id)), std::move(after), Change::Structure);
    return QString::fromStdString(m.id);
}

QString ModelDocument::add_link(LiaKind kind, const QString& from, const QString& to) {
    const Mat* a = model_.find_mat(from.toStdString());
    const Mat* b = model_.find_mat(to.toStdString());
    if (!a || !b || a == b) return {};
    Lia l;
    l.kind = kind;
    l.id = fresh_id(kind == LiaKind::Damper   ? "damper"
                    : kind == LiaKind::Buffer ? "buffer"
                                              : "k")
               .toStdString();
    l.from = a->id, l.to = b->id;
    // The faster of the two rates: a link never makes its MATs wait for it.
    auto divider = [&](const Mat* m) {
        const RateLevel* r = model_.find_rate(m->rate);
        return r ? r->divider : 1;
    };
    l.rate = divider(a) <= divider(b) ? a->rate : b->rate;
    if (kind != LiaKind::Damper) l.stiffness = 100.0;
    if (kind != LiaKind::Spring) l.damping = 0.01;
    Model after = model_;
    after.lias.push_back(l);
    push(tr("Connect %1 to %2").arg(from, to), std::move(after), Change::Structure);
    return QString::fromStdString(l.id);
}

void ModelDocument::remove(const QStringList& ids) {
    std::set<std::string> gone;
    for (const QString& id : ids) gone.insert(id.toStdString());
    Model after = model_;
    auto uses_gone = [&](const Lia& l) {
        return gone.count(l.id) || gone.count(l.from) || gone.count(l.to) ||
               (!l.press.empty() && gone.count(l.press)) ||
               (!l.surface.empty() && gone.count(l.surface));
    };
    for (auto& l : after.lias) {
        if (l.kind == LiaKind::Finger) {  // a finger keeps the rest of its string, if any
            std::erase_if(l.along, [&](const std::string& id) { return gone.count(id) > 0; });
            if (l.along.size() < 2) gone.insert(l.id);
            continue;
        }
        if (uses_gone(l)) gone.insert(l.id);
    }
    std::erase_if(after.lias, [&](const Lia& l) { return gone.count(l.id) > 0; });
    std::erase_if(after.mats, [&](const Mat& m) { return gone.count(m.id) > 0; });
    for (auto& m : after.mats) {  // modal points reading a deleted mode lose it
        for (std::size_t k = m.modes.size(); k-- > 0;)
            if (gone.count(m.modes[k])) {
                m.modes.erase(m.modes.begin() + static_cast<long>(k));
                m.weights.erase(m.weights.begin() + static_cast<long>(k));
            }
    }
    std::erase_if(after.probes, [&](const Probe& p) { return gone.count(p.element) > 0; });
    std::erase_if(after.outputs, [&](const Output& o) { return gone.count(o.element) > 0; });
    std::erase_if(after.controls, [&](const Control& c) {
        return gone.count(c.target.element) || (!c.element.empty() && gone.count(c.element));
    });
    if (after.mats.size() == model_.mats.size() && after.lias.size() == model_.lias.size()) return;
    push(ids.size() == 1 ? tr("Delete %1").arg(ids.front())
                         : tr("Delete %1").arg(elements(ids.size())),
         std::move(after), Change::Structure);
}

void ModelDocument::move(const QStringList& ids, QPointF delta, bool continuing_drag) {
    Model after = model_;
    for (const QString& id : ids)
        if (Mat* m = after.find_mat(id.toStdString())) {
            const QPointF p = position_of(*m) + delta;
            m->display = std::make_pair(p.x(), p.y());
        }
    push(tr("Move"), std::move(after), Change::Layout, ids.join(','), {},
         continuing_drag ? kMoveMerge : -1);
}

// The edge where a value enters: the table's range and the whole model (stability at the
// running rate) are checked here, once, in place; the walk on to the engine trusts it.
void ModelDocument::edit_parameter(const ParameterName& name, double value) {
    const double before = get_parameter(model_, name);  // throws for a bad name
    {
        const RunningRate at(model_, running_rate_);
        set_parameter_validated(model_, name, value);
    }
    undo_.push(new ParameterEdit(*this, name, before, value));  // its first redo() announces it
}

void ModelDocument::move_bow(double beta) {
    Model after = model_;
    set_variant_parameter(after, "bow.position", beta);
    if (bow_position(after) == bow_position(model_)) return;  // β is still nearest the same mass
    {
        const RunningRate at(after, running_rate_);
        validate_model(after);
    }
    const QString bow = QString::fromStdString(first_bow(after)->id);  // (the move needs one)
    push(tr("Move the bow to β = %1").arg(beta, 0, 'g', 4), std::move(after), Change::BowMove, bow,
         "position");
}

void ModelDocument::set_rate(const QString& id, const QString& rate) {
    if (!model_.find_rate(rate.toStdString()))
        throw InputError(rate.toStdString(), "is not a rate level of this model");
    Model after = model_;
    if (Mat* m = after.find_mat(id.toStdString())) m->rate = rate.toStdString();
    if (Lia* l = after.find_lia(id.toStdString())) l->rate = rate.toStdString();
    push(tr("Move %1 to rate %2").arg(id, rate), std::move(after), Change::Structure);
}

QString ModelDocument::copy(const QStringList& ids) const {
    std::set<std::string> chosen;
    for (const QString& id : ids) chosen.insert(id.toStdString());
    Model part;
    part.name = "clipboard";
    part.rates = model_.rates;
    // Each with where it is drawn, so that the copy is pasted beside it.
    for (Mat m : model_.mats)
        if (chosen.count(m.id)) {
            const QPointF at = position_of(m);
            m.display = std::make_pair(at.x(), at.y());
            part.mats.push_back(std::move(m));
        }
    for (const auto& l : model_.lias)
        if (l.kind != LiaKind::BowFriction && chosen.count(l.from) && chosen.count(l.to))
            part.lias.push_back(l);
    return QString::fromStdString(format_model(part));
}

QStringList ModelDocument::paste(const QString& text, QPointF offset) {
    Model part;
    try {
        part = parse_model(text.toStdString(), "clipboard");
    } catch (const std::exception&) {
        return {};  // not something the studio copied
    }
    Model after = model_;
    std::map<std::string, std::string> renamed;
    QStringList added;
    auto unused = [&](const std::string& id) {
        std::string candidate = id;
        for (int n = 2; after.find_mat(candidate) || after.find_lia(candidate); ++n)
            candidate = id + "_" + std::to_string(n);
        return candidate;
    };
    const QPointF shift = paste_shift(part, offset);
    for (Mat m : part.mats) {
        if (!after.find_rate(m.rate)) m.rate = after.rates.front().id;
        m.kind = m.kind == MatKind::ModalPoint ? MatKind::Mass : m.kind;
        if (m.kind == MatKind::Mass && m.mass <= 0) m.mass = 1e-3;
        m.modes.clear(), m.weights.clear();
        const std::string id = unused(m.id);
        renamed[m.id] = id;
        m.id = id;
        const QPointF p =
            QPointF(m.display ? m.display->first : 0, m.display ? m.display->second : 0) + shift;
        m.display = std::make_pair(p.x(), p.y());
        added << QString::fromStdString(id);
        after.mats.push_back(m);
    }
    for (Lia l : part.lias) {
        if (!renamed.count(l.from) || !renamed.count(l.to)) continue;
        l.from = renamed[l.from], l.to = renamed[l.to];
        if (!after.find_rate(l.rate)) l.rate = after.rates.front().id;
        l.id = unused(l.id);
        added << QString::fromStdString(l.id);
        after.lias.push_back(l);
    }
    if (added.isEmpty()) return {};
    push(tr("Paste %1").arg(elements(added.size())), std::move(after), Change::Structure);
    return added;
}

// `offset` from the originals, or a multiple of it where an earlier paste already lies there.
QPointF ModelDocument::paste_shift(const Model& part, QPointF offset) const {
    constexpr double kSamePlace = 1;  // scene units
    constexpr int kMostPastes = 50;
    auto taken = [&](QPointF shift) {
        for (const Mat& pasted : part.mats) {
            if (!pasted.display) continue;
            const QPointF at = QPointF(pasted.display->first, pasted.display->second) + shift;
            for (const Mat& m : model_.mats)
                if ((position_of(m) - at).manhattanLength() < kSamePlace) return true;
        }
        return false;
    };
    QPointF shift = offset;
    for (int n = 1; n < kMostPastes && taken(shift); ++n) shift += offset;
    return shift;
}

}  // namespace archet::ui
