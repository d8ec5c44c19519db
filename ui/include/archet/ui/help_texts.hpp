#pragma once
// What the Help menu shows: the keyboard shortcuts, where the user guide is, and About (the
// version and the licences of the libraries the studio is built with).

#include <QString>

namespace archet::ui {

/// Every shortcut of the studio, as an HTML table.
QString shortcut_table();
/// Version and libraries, as HTML.
QString about_text();
/// The user guide's file: installed with the package, or in the source tree beside the
/// binaries; empty when neither is there.
QString user_guide_path();

}  // namespace archet::ui
