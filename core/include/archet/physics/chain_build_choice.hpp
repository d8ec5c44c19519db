#pragma once
// Which build of the bowed chain's loop runs a model fastest on this CPU, found by timing the
// builds on the simulation itself, as FFTW's planner times its candidates. Every build gives the
// same bytes, and which is fastest depends on the model as much as on the CPU: on an Intel Xeon
// (Emerald Rapids) the paper's 60-mass chaplet ran in 0.85 of its AVX-512 time with AVX2, where
// a 1,024-mass chain took 1.3 times as long (512-bit arithmetic leaves the step's scalar work
// two ports of three).

#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/simulation.hpp"

namespace archet {

/// The build of the bowed chain's loop (Simulation::set_chain_build()) that ran `sim` fastest,
/// from its state and on its gesture track, over a few alternated trials of about a fifth of a
/// millisecond each, after which `sim` resumes exactly where it was (save_state(), load_state()):
/// the widest build this CPU runs (chosen_chain_build()) unless the other was faster by more than
/// kClearMargin, or the model does not run as a bowed chain. Takes a few milliseconds and
/// allocates: not for a real-time thread.
ChainBuild fastest_chain_build(Simulation& sim);

/// How much faster than the widest build another must be to be chosen: within it, the timing
/// of a shared machine decides as much as the builds do.
inline constexpr double kClearMargin = 0.03;

}  // namespace archet
