#pragma once
// analyse_modes(), made again only when what it reads of the model has changed: the studio's
// Modes panel asks after every edit, and an edit of the bow's force or friction, of the hand or
// of the gesture leaves the sounding part (to the bit), which DOFs are supports and what the
// modal points read as they were, so the same modes. A long string's analysis takes seconds
// (7.3 s for a 41 Hz string of 578 masses). Only the last analysis is kept.

#include <cstddef>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "archet/analysis/modal_analysis.hpp"
#include "archet/model/linear_system.hpp"
#include "archet/model/model.hpp"

namespace archet {

class ModalAnalysisCache {
  public:
    /// analyse_modes(model): the same result, and what it throws. Safe from several threads.
    ModalAnalysis of(const Model& model);
    /// How many analyses it has made rather than given again.
    std::size_t solves() const;

  private:
    /// Everything of the model analyse_modes() reads.
    struct Inputs {
        LinearSystem system;
        std::vector<bool> supports;
        ModalPointReads points;
        bool same_as(const Inputs& other) const;
    };

    mutable std::mutex mutex_;
    std::optional<std::pair<Inputs, ModalAnalysis>> last_;
    std::size_t solves_ = 0;
};

}  // namespace archet
