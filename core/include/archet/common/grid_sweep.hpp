#pragma once
// Sweeps over a grid of independent points (playability and attack maps): the points one shard
// of a sweep plays, played on every core, and the shards' points joined back into the grid.

#include <algorithm>
#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "archet/common/input_error.hpp"
#include "archet/common/parallel_for.hpp"

namespace archet {

/// The points of a grid of `count` that shard I of N plays (index % N == I); InputError
/// "--shard" unless 0 ≤ I < N.
std::vector<std::size_t> shard_points(std::size_t count, int shard, int shards);

/// Plays `play(index)` for every point of the shard on `jobs` threads, calling
/// `progress(done, total)` from the caller's thread; the points in index order. A point that
/// throws, or `*cancel` ("cancelled"), ends it with an InputError naming `what`.
template <class Point>
std::vector<Point> sweep_grid(const std::string& what, std::size_t count, int jobs, int shard,
                              int shards, const std::function<Point(std::size_t)>& play,
                              const std::function<void(std::size_t, std::size_t)>& progress,
                              const std::atomic<bool>* cancel) {
    const std::vector<std::size_t> mine = shard_points(count, shard, shards);
    std::vector<Point> points(mine.size());
    bool finished = false;
    try {
        finished = parallel_for(
            mine.size(), jobs, [&](std::size_t k) { points[k] = play(mine[k]); }, cancel, progress);
    } catch (const std::exception& e) {
        throw InputError(what, e.what());
    }
    if (!finished) throw InputError(what, "cancelled");
    return points;
}

/// Sorts the points of merged shards by index and checks that they hold each of the grid's
/// `count` points once; InputError naming `part` otherwise.
template <class Point>
void check_shards_cover(std::vector<Point>& points, std::size_t count, const std::string& part) {
    std::sort(points.begin(), points.end(), [](auto& x, auto& y) { return x.index < y.index; });
    for (std::size_t i = 0; i < count; ++i)
        if (i >= points.size() || points[i].index != i)
            throw InputError(part, "the shards do not cover the grid: point " + std::to_string(i) +
                                       " is missing or repeated");
    if (points.size() != count) throw InputError(part, "the shards hold more points than the grid");
}

}  // namespace archet
