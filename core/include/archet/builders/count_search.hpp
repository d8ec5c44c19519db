#pragma once
// Where the full-bandwidth builder starts its search for the string's mass count.

#include <functional>

namespace archet {

/// A count in [low, high] (low ≤ high) from which a search down for the largest count that
/// keeps a reserve finds what a search from `high` finds: `high`, or a count that lacks the
/// reserve, as every larger one then does (assumed: if keeps(n), then keeps(m) for every m < n).
/// `roughly_keeps` is a cheap estimate of `keeps`, possibly wrong near the edge; it only saves
/// calls of `keeps`, which is asked only of counts above `low`. Calls `cancelled` between tests
/// (it throws to cancel).
int count_search_start(
    int low, int high, const std::function<bool(int)>& roughly_keeps,
    const std::function<bool(int)>& keeps, const std::function<void()>& cancelled = [] {});

}  // namespace archet
