#pragma once
// A one-line label that never widens its window: text longer than its room ends in "…", and
// the whole text is its tooltip. For the status bar's long engine and device texts.

#include <QLabel>

namespace archet::ui {

class ElidedLabel : public QLabel {
    Q_OBJECT

  public:
    explicit ElidedLabel(QWidget* parent = nullptr);
    void set_full_text(const QString& text);
    const QString& full_text() const { return full_; }
    QSize minimumSizeHint() const override;

  protected:
    void resizeEvent(QResizeEvent*) override;

  private:
    void elide();
    QString full_;
};

}  // namespace archet::ui
