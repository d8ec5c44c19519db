#pragma once
// The bounds every input is checked against before any work starts, so that no file, gesture
// or command line can make Archet read, compute or write without end. They are generous for
// physics (an hour of sound, half a million elements) and documented in docs/user-guide.md
// ("Limits"); the commands that can sensibly go further take a flag to raise theirs.

#include <cstddef>
#include <cstdint>

namespace archet::limits {

/// Bytes a model, gesture or take file may hold (a 200,000-mass chain is about 40 MB).
inline constexpr std::uintmax_t kFileBytes = 64u << 20;
/// Masses plus links plus controls in one model.
inline constexpr std::size_t kElements = 500'000;
/// Probes of one model (columns of a probe CSV).
inline constexpr std::size_t kProbes = 1024;
/// Seconds a gesture, an envelope or a render may last (render: raise with --max-duration).
inline constexpr double kDurationSeconds = 3600.0;
/// The range of a master clock, Hz.
inline constexpr double kMinSampleRate = 1000.0;
inline constexpr double kMaxSampleRate = 1'000'000.0;
/// Points of a playability map (raise with --max-points).
inline constexpr std::size_t kMapPoints = 100'000;
/// Values of one comparison: each is rendered, kept in memory and drawn side by side.
inline constexpr std::size_t kCompareValues = 64;

// Physical ranges of state and gestures, in SI units: far beyond any instrument, and small
// enough that energies (m·v², k·x²) stay finite in double precision.
inline constexpr double kPosition = 1e4;    ///< m, positions and gesture slide
inline constexpr double kPress = 1.0;       ///< m, gesture press (a device's travel is cm)
inline constexpr double kVelocity = 100.0;  ///< m/s, initial velocities, gesture speeds
inline constexpr double kMass = 1e6;        ///< kg
inline constexpr double kStiffness = 1e12;  ///< N/m
inline constexpr double kDamping = 1e9;     ///< N·s/m
inline constexpr double kScale = 1e6;       ///< gesture position and force scales
inline constexpr double kOutputGain = 1e6;  ///< output_gain and output gains, 1/N or 1/m

}  // namespace archet::limits
