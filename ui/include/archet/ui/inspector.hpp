#pragma once
// The selected element's parameters, with their units and ranges, and the stability margin
// of its rate level; on the bow (its module, contact or mass), where it meets the string. A value
// is checked before it is applied: one out of range, or one that would make the scheme unstable, is
// refused with the reason and the model is left as it was.

#include <QString>
#include <QWidget>
#include <functional>

class QFormLayout;
class QLabel;
class QLineEdit;

namespace archet::ui {

class ModelDocument;

class Inspector : public QWidget {
    Q_OBJECT

  public:
    explicit Inspector(ModelDocument& document, QWidget* parent = nullptr);

    void show_element(const QString& id);
    const QString& element() const { return element_; }
    /// What the last refused edit said (empty when the last edit was applied).
    const QString& warning() const { return warning_; }
    /// Applies a typed value as the field would; returns whether it was applied.
    bool edit(const QString& parameter, double value);
    /// Moves the bow to β as its field would (ModelDocument::move_bow()); returns whether it
    /// moved.
    bool move_bow(double beta);

  private:
    /// Makes `change`, or says why it was refused and shows the value still in force.
    bool apply(const std::function<void()>& change);
    QLineEdit* number_field(const QString& name, const QString& text,
                            const std::function<void(double)>& typed);
    void rebuild();
    void add_bow_position(const std::string& id);
    void show_stability();

    ModelDocument& document_;
    QString element_;
    QString warning_;
    QLabel* title_;
    QLabel* stability_;
    QLabel* warning_label_;
    QWidget* fields_;
    QFormLayout* form_;
};

}  // namespace archet::ui
