#pragma once
// The first modes of models whose sounding parts are the same, solved once: a comparison's
// variants of a bow or a hand (its position, force, speed) leave the string as it was, to the
// bit, and the eigenvalue solve of its update is most of what a short variant costs. Threads
// may ask at once: the first to ask for a sounding part solves it, the others wait for it. A
// string with a finger takes the whole analysis each time (string_first_mode() says why).
// (SoundingPartSolves keeps the solves.)

#include <cstddef>

#include "archet/analysis/discrete_modes.hpp"
#include "archet/analysis/sounding_part_solves.hpp"
#include "archet/analysis/string_first_mode.hpp"
#include "archet/model/linear_system.hpp"
#include "archet/model/model.hpp"

namespace archet {

class SharedFirstModes {
  public:
    /// string_first_mode(model), with the same bits, and what it throws; the roots of its
    /// sounding part are solved only where no model asked before had an identical() one.
    StringFirstMode of(const Model& model);
    /// How many sounding parts it has solved.
    std::size_t solves() const { return roots_.solves(); }

  private:
    SoundingPartSolves<UpdateRoots> roots_;  ///< all of a comparison's
};

}  // namespace archet
