/**
 * \file event_margin.hpp
 * \brief The margin by which a cache-blocked step stays below an exact event target (`collisions_per_particle`).
 *
 * The blocks of a step run independently, so a blocked step cannot stop at a given event; near an exact target
 * it is shortened until its events surely stay below it, and the last events are made on the whole gas, which
 * stops exactly (collide.hpp, "Blocks", "Event targets"; agg_frag.hpp, "Cache blocks"; \ref sch_blocks
 * "docs/schemes.md", \ref af_blocks "docs/agg-frag.md"). A step expected to bring mu events may reach the
 * `remaining` ones when
 *   1.1 mu + 8 sqrt(mu) + 16 > remaining:
 * 10 % for a rate that rises within the step, 8 standard deviations of a count whose variance is at most its
 * mean (Poisson, or binomial thinning of it), and 16 events for the smallest counts. largest_safe_mean()
 * is the inverse: the largest mu that may not reach them, the root of 1.1 s^2 + 8 s + 16 - remaining = 0
 * in s = sqrt(mu), s = (-8 + sqrt(64 + 4.4 (remaining - 16)))/2.2 (0 for 16 events or fewer).
 *
 * Used by collide::Collider (the particle blocks) and agg_frag::Gas (the cluster blocks); checked by
 * EventMargin.HandComputedValues (tests/collide_test.cpp).
 */
#pragma once

#include <cmath>

namespace gdsmc::event_margin {

/// Whether a step expected to bring `mean` events could reach the `remaining` ones (file comment).
inline bool may_reach(double mean, double remaining) { return 1.1 * mean + 8.0 * std::sqrt(mean) + 16.0 > remaining; }

/// The largest expected event count of a step that may not reach `remaining` events (file comment); 0 when
/// `remaining` is 16 or less.
inline double largest_safe_mean(double remaining) {
  if (remaining <= 16.0) return 0.0;
  const double root = (-8.0 + std::sqrt(64.0 + 4.4 * (remaining - 16.0))) / 2.2;
  return root * root;
}

}  // namespace gdsmc::event_margin
