#pragma once
// The model being edited in the studio, with its undo history. Every edit (add, connect,
// delete, move, paste, a parameter, a rate) is one undoable step that stores the model
// before and after it: simple, and exact whatever the edit touched. Listeners learn what
// kind of change it was, so that a parameter glides into the running engine while a new
// element reloads it.

#include <QObject>
#include <QPointF>
#include <QString>
#include <QStringList>
#include <QUndoStack>

#include "archet/model/model.hpp"
#include "archet/model/parameter_name.hpp"
#include "archet/model/stability_limit.hpp"

namespace archet::ui {

class ModelDocument : public QObject {
    Q_OBJECT

  public:
    /// Parameter: a fresh edit, validated. ReplayedParameter: one set back or again by undo
    /// or redo, to a value that was not checked against the model as it is now. BowMove: the
    /// bow module moved along the string (`bow.position`), which a playing string goes on
    /// through; `element` is the bow module.
    enum class Change { Structure, Parameter, ReplayedParameter, Layout, BowMove };

    explicit ModelDocument(QObject* parent = nullptr);

    const Model& model() const { return model_; }
    QUndoStack& undo_stack() { return undo_; }
    /// Starts editing `model` afresh (no undo history); `path` is its file, if any.
    void reset(const Model& model, const QString& path = {});
    const QString& path() const { return path_; }
    void set_path(const QString& path);
    bool modified() const { return !undo_.isClean(); }
    void mark_saved() { undo_.setClean(); }

    // ---- edits: each one step of the undo history ----
    /// A new MAT of `kind` at `at`, on `rate`; returns its id (kind name and a number).
    QString add_mat(MatKind kind, QPointF at, const QString& rate = "audio");
    /// A link of `kind` from one MAT to another, at the faster of their rates; returns its id.
    QString add_link(LiaKind kind, const QString& from, const QString& to);
    /// Deletes elements, with the links, probes, outputs and controls that need them.
    void remove(const QStringList& ids);
    /// Moves MATs on the canvas; a drag's successive moves merge into one step.
    void move(const QStringList& ids, QPointF delta, bool continuing_drag);
    /// Throws InputError (with the reason) for an unknown name, a value out of range, or one
    /// that makes the model fail validation (e.g. the scheme's stability bound). A parameter
    /// change keeps a valid model valid: listeners need not check it again.
    void edit_parameter(const ParameterName& name, double value);
    void set_rate(const QString& id, const QString& rate);
    /// Moves the bow module to the string mass nearest β, the bow's distance from the bridge
    /// over the string's length (set_variant_parameter()'s `bow.position`); a β nearest the mass
    /// it bows already changes nothing (no undo step). Throws InputError
    /// for a β outside (0, 0.5), a model that is not a bowed chain of masses s1…sN, or a move
    /// that leaves the model invalid at the running rate.
    void move_bow(double beta);

    /// The selected MATs and the links among them, as model JSON (for the clipboard).
    QString copy(const QStringList& ids) const;
    /// Adds what copy() produced, renamed where ids are taken, `offset` from where the
    /// originals are drawn (again `offset` further while an earlier paste lies there);
    /// returns the new ids.
    QStringList paste(const QString& text, QPointF offset);

    /// The position of a MAT on the canvas (assigned when the model had none).
    QPointF position_of(const Mat& mat) const;

    /// The rate the model runs at (the engine's device may not run at the model's own rate):
    /// edits are validated at it. 0, the default: the model's own rate.
    void set_running_rate(double hz) { running_rate_ = hz; }
    /// Validates the model as it would run: at the running rate when there is one. Throws
    /// InputError for the first problem.
    void validate();
    /// How far a parameter may go before the scheme turns unstable (stability_limit.hpp),
    /// probed in the document's model and put back: no copy per field the inspector shows.
    std::optional<StabilityLimit> stability_limit(const ParameterName& name);

  signals:
    /// After every change, undo and redo included. For a parameter, `element` and `name`
    /// say which (its new value is in model()).
    void changed(archet::ui::ModelDocument::Change change, const QString& element,
                 const QString& name);
    void path_changed(const QString& path);
    /// After reset(): another model, not an edit of this one.
    void replaced();

  private:
    friend class ModelEdit;
    friend class ParameterEdit;
    void apply(const Model& model, Change change, const QString& element, const QString& name);
    void apply_parameter(const ParameterName& name, double value, Change change);
    void push(const QString& text, Model after, Change change, const QString& element = {},
              const QString& name = {}, int merge = -1);
    QString fresh_id(const QString& stem) const;
    QPointF paste_shift(const Model& part, QPointF offset) const;

    Model model_;
    double running_rate_ = 0;
    QString path_;
    QUndoStack undo_;
};

}  // namespace archet::ui
