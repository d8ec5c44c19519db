#pragma once
// The model's modes from modal analysis (exact for the scheme): frequency, decay, and each
// partial against the harmonic series in cents, in a table and a plot.

#include <QWidget>

class QCustomPlot;
class QLabel;
class QTableWidget;

namespace archet::ui {

class ModelDocument;

class ModesPanel : public QWidget {
    Q_OBJECT

  public:
    /// The cents chart shows at least ±5 cents: finer deviations the ear does not hear.
    static constexpr double kCentsSpan = 10;

    explicit ModesPanel(ModelDocument& document, QWidget* parent = nullptr);
    int mode_count() const;
    double fundamental() const { return fundamental_; }

  private:
    void refresh();

    ModelDocument& document_;
    QLabel* summary_;
    QTableWidget* table_;
    QCustomPlot* cents_;
    double fundamental_ = 0;
};

}  // namespace archet::ui
