#pragma once
// Variants of a model side by side, as in the paper's Fig. 5: for each, the bow force over
// the last periods and the bow force against the displacement at the bowing point, titled
// with the value and the energy the string dissipates per period. Shown in the compare view
// and written as a PNG by `archet compare`.

#include <QWidget>
#include <vector>

#include "archet/analysis/comparison.hpp"

class QGridLayout;

namespace archet::ui {

class CompareFigure : public QWidget {
    Q_OBJECT

  public:
    explicit CompareFigure(QWidget* parent = nullptr);
    void show_runs(const std::vector<ComparisonRun>& runs);
    /// Renders the figure at `size` into a PNG (or PDF, by the suffix).
    bool save(const QString& path, QSize size = {1400, 800});
    int columns() const { return columns_; }

  private:
    QGridLayout* grid_;
    int columns_ = 0;
};

}  // namespace archet::ui
