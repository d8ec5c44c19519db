#include "archet/builders/count_search.hpp"

#include <algorithm>

namespace archet {

// Down on the estimate to the largest count it keeps, one up from there, and up again while
// the exact test keeps that count too (where the estimate was too cautious).
int count_search_start(int low, int high, const std::function<bool(int)>& roughly_keeps,
                       const std::function<bool(int)>& keeps,
                       const std::function<void()>& cancelled) {
    int start = high;
    while (start > low && !roughly_keeps(start)) {
        cancelled();
        --start;
    }
    start = std::min(high, start + 1);
    while (start < high) {
        cancelled();
        if (!keeps(start)) break;
        ++start;
    }
    return start;
}

}  // namespace archet
