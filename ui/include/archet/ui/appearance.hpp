#pragma once
// Light or dark: the studio follows the desktop (the platform theme's palette, or GNOME's and
// GTK's dark preference when the platform gives Qt none) unless the user picks one in
// View → Appearance. Remembered between runs.

#include <QString>

namespace archet::ui {

enum class Appearance { Desktop, Light, Dark };

/// Applies the appearance to the whole application (Fusion's light or dark palette, or the
/// desktop's). Every plot restyles itself (plot_palette).
void apply_appearance(Appearance appearance);
/// Whether the desktop asks for dark: GTK_THEME ending in ":dark", or GNOME's color-scheme.
bool desktop_prefers_dark();

Appearance saved_appearance();
void save_appearance(Appearance appearance);

}  // namespace archet::ui
