#pragma once
// One tick of a hand link, for the general step (compute_hand_link_forces()) and the bowed
// chain's loop, which keeps its hand links in a frame of its own: both hold the same fields.
// Private to the physics sources.

namespace archet::hand_link {

struct Tick {
    double d;          ///< x(a) − x(b) now
    double end_force;  ///< the force the link's end takes
    double work;       ///< the hand's work over the tick, in the scheme's energy
};

/// Where the link sees the hand now: along the line from its previous position to its newest,
/// `done` of the way through the hand's period (seen_position() says why).
[[gnu::always_inline]] inline double hand_seen_at(double from, double to, double done) {
    return from + (to - from) * done;
}
[[gnu::always_inline]] inline double hand_seen_at(const double* hand_x_prev, const double* hand_x,
                                                  int index, double done) {
    return hand_seen_at(hand_x_prev[index], hand_x[index], done);
}

/// The link's force from where it sees the hand now and where its end is, its state carried to
/// the next tick, and its sums over the hand's period.
template <class Link>
[[gnu::always_inline]] inline Tick tick(Link& l, double hand, double end) {
    // x(a) − x(b), and the force the end takes: a negation rather than a product with
    // hand_sign (the same bits, a shorter wait for the friction solve downstream).
    const double gap = hand - end;
    const double d = l.hand_is_a ? gap : -gap;
    const double d_prev = l.d_prev, force = l.force;
    const double f = l.k * (d - l.length) + l.zdt * (d - d_prev);
    const double end_force = l.hand_is_a ? f : -f;
    const double work = l.hand_sign * 0.5 * (force + f) * (hand - l.hand_seen);
    l.d_before = d_prev, l.d_prev = d, l.force = f, l.hand_seen = hand;
    // The hand's point takes the mean force over its period when it ticks.
    l.hand_force_sum -= end_force;
    l.hand_work_sum += work;
    return {d, end_force, work};
}

/// At the hand's tick: its point takes the link's mean force over the period (`weight` is the
/// link's share of it) and the work the link booked, and the sums start again.
template <class Link, class GesturePoint>
[[gnu::always_inline]] inline void hand_over(Link& l, double weight, double& hand_force,
                                             GesturePoint& point) {
    const double mean = l.hand_force_sum * weight;
    hand_force += mean;
    point.faster_links_force += mean;
    point.faster_links_work += l.hand_work_sum;
    l.hand_force_sum = l.hand_work_sum = 0.0;
}

}  // namespace archet::hand_link
