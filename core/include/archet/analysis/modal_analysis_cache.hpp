#pragma once
// analyse_modes(), with its eigenvalue solve made again only when the sounding part changes:
// the studio's Modes panel asks after every edit, and an edit of the bow (its force, friction or
// place on the string), of the hand or of the gesture leaves the sounding part as it was, to the
// bit. The modes are then classed again for the model as it is (class_modes(): which DOFs are
// supports, what the modal points read), a small part of the work. A long string's solve takes
// seconds (7.3 s for a 41 Hz string of 578 masses). The last few solves are kept, so that an
// undo back to a string analysed before finds its solve (SoundingPartSolves).

#include <cstddef>

#include "archet/analysis/modal_analysis.hpp"
#include "archet/analysis/sounding_part_solves.hpp"
#include "archet/model/model.hpp"

namespace archet {

class ModalAnalysisCache {
  public:
    /// analyse_modes(model): the same result, to the bit, and what it throws. Safe from several
    /// threads.
    ModalAnalysis of(const Model& model);
    /// How many eigenvalue solves it has made.
    std::size_t solves() const;

    /// How many solves it keeps, the most recently used (a long string's is a few MB).
    static constexpr std::size_t kKept = 4;

  private:
    SoundingPartSolves<ModalSolve> solves_{kKept};
};

}  // namespace archet
