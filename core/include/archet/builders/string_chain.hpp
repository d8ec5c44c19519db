#pragma once
// The string of the bowed-string builder: its chaplet of masses s1..sN and links k0..kN
// between the bridge and the nut, tuned homogeneous or harmonic, and its exact modal
// equivalent.

#include "archet/analysis/discrete_modes.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/builders/harmonic_chain.hpp"
#include "archet/builders/string_losses.hpp"

namespace archet {

/// Link damping as a share of stiffness (z = ratio·k) the options set during tuning: the
/// paper's (from string_t60, or --string-damping); 0 when the losses are solved afterwards.
double link_damping_ratio(const BowedStringOptions& o, const ChainProfile& profile);

/// The chaplet of `n` masses tuned to the pitch under the scheme, with its bridges and body. A
/// harmonic chaplet given its `losses` is tuned with them: the scheme's dampers pull its upper
/// partials by several cents, which the tuning then corrects.
Model tuned_string(const BowedStringOptions& o, int n, const StringLosses* losses = nullptr);

/// Whether tuned_string() ends with corrections on the damped modes, each a dense
/// eigenproblem of twice the string's size: a harmonic chaplet not damped while it is tuned.
bool tuning_ends_on_damped_modes(const BowedStringOptions& o);

/// tuned_string() without those corrections for its bridges' dampers, for a fraction of its
/// time (tuned_string() itself when its tuning has no such corrections). At 110 Hz, with the
/// bow, its use of the stability limit is within 0.07 % of the fully tuned string's.
Model undamped_tuned_string(const BowedStringOptions& o, int n);

/// Puts the damped first mode, as the scheme runs it, exactly on the pitch: the chain is tuned
/// undamped, and the losses (and a body) then move it by a fraction of a cent. Scaling each
/// link's stiffness and damping together keeps σ1. Returns the roots of the model's update as
/// it leaves it (its audio level's system), which the last check has already solved: its
/// modes (discrete_modes()), and its string's first mode once it is bowed.
UpdateRoots retune_damped(Model& model, const BowedStringOptions& o, int n);

/// The ids of the string's masses and links in a chain of `n` masses.
StringElements string_elements(int n);

/// Replaces the chain s1..sN by its exact modal equivalent: one damped oscillator per mode,
/// with a modal point at each mass s1..sN (the step moves those the links and the bow read: s1,
/// sN and the bowed mass's or the bow's contact; the others only show the string's shape). `losses`
/// are the string's (σ0 from the masses' dampers to their rest points, σ1 from the links', both
/// proportional: modal). With `wide_bow` a contact point (kBowContact, before the bowed point)
/// reads ¼, ½, ¼ of the shapes at the bowed mass and its neighbours.
void make_modal(Model& model, int n, int bowed, const StringLosses& losses, bool wide_bow);

/// The string mass the bow sits on for bow position β (with a neighbour on each side).
int bowed_mass(const BowedStringOptions& o, int n);

/// The length (m) of the string `o` describes: its tension and density make waves travel at
/// √(T/ρ), and its first mode at the pitch takes two lengths per period.
double string_length(const BowedStringOptions& o);

}  // namespace archet
