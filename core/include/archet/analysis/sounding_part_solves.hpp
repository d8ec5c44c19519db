#pragma once
// Solves of sounding parts, kept by the part they solved: an analysis asked again for a string
// identical() to one solved before (a bow moved along it, a hand, an undo) takes that solve
// instead of making it again. Threads may ask at once: the first to ask for a part solves it
// outside the lock, the others wait for that solve. A solve that throws throws to those waiting
// and is not kept. Serves SharedFirstModes (roots of the update) and ModalAnalysisCache (the
// modal analysis's solve).

#include <algorithm>
#include <cstddef>
#include <deque>
#include <exception>
#include <future>
#include <iterator>
#include <mutex>
#include <utility>

#include "archet/model/linear_system.hpp"

namespace archet {

template <class Solve>
class SoundingPartSolves {
  public:
    /// Keeps the `kept` most recently used solves; 0 keeps them all.
    explicit SoundingPartSolves(std::size_t kept = 0) : kept_(kept) {}

    /// The solve of `system`: one kept for an identical() system, else `make(system)`.
    template <class Make>
    Solve of(const LinearSystem& system, Make&& make) {
        std::promise<Solve> solving;
        std::shared_future<Solve> solve;
        bool mine = false;
        {
            const std::lock_guard lock(mutex_);
            const auto found = find(system);
            if (found != parts_.end()) {
                solve = found->second;
                std::rotate(parts_.begin(), found, std::next(found));  // now the most recent
            } else {
                solve = solving.get_future().share();
                parts_.emplace_front(system, solve);
                if (kept_ > 0 && parts_.size() > kept_) parts_.pop_back();
                mine = true;
            }
        }
        if (mine) {
            try {
                solving.set_value(make(system));  // outside the lock: seconds on a long string
                const std::lock_guard lock(mutex_);
                ++solves_;
            } catch (...) {
                solving.set_exception(std::current_exception());
                const std::lock_guard lock(mutex_);
                if (const auto found = find(system); found != parts_.end()) parts_.erase(found);
            }
        }
        return solve.get();
    }

    /// How many solves it has made (those that threw not counted).
    std::size_t solves() const {
        const std::lock_guard lock(mutex_);
        return solves_;
    }

  private:
    using Parts = std::deque<std::pair<LinearSystem, std::shared_future<Solve>>>;
    typename Parts::iterator find(const LinearSystem& system) {
        return std::find_if(parts_.begin(), parts_.end(),
                            [&](const auto& part) { return identical(part.first, system); });
    }

    const std::size_t kept_;
    mutable std::mutex mutex_;
    Parts parts_;  ///< most recently used first
    std::size_t solves_ = 0;
};

}  // namespace archet
