#pragma once
// Writes a widget (scopes, a comparison) as an image: PNG, or PDF (vector) by the suffix.

#include <QSize>
#include <QString>

class QWidget;

namespace archet::ui {

/// Renders `widget` at `size` (its current size when empty); returns whether it was written.
bool save_widget_image(QWidget& widget, const QString& path, QSize size = {});

}  // namespace archet::ui
