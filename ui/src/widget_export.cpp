#include "archet/ui/widget_export.hpp"

#include <QLayout>
#include <QPageSize>
#include <QPainter>
#include <QPdfWriter>
#include <QWidget>

namespace archet::ui {

bool save_widget_image(QWidget& widget, const QString& path, QSize size) {
    if (size.isValid()) widget.resize(size);
    widget.ensurePolished();
    if (widget.layout()) widget.layout()->activate();
    if (path.endsWith(".pdf", Qt::CaseInsensitive)) {
        QPdfWriter pdf(path);
        pdf.setPageSize(QPageSize(QSizeF(widget.size()), QPageSize::Point));
        pdf.setPageMargins({});
        QPainter painter(&pdf);
        if (!painter.isActive()) return false;
        const double scale = pdf.width() / static_cast<double>(widget.width());
        painter.scale(scale, scale);
        widget.render(&painter);
        return true;
    }
    return widget.grab().save(path);
}

}  // namespace archet::ui
