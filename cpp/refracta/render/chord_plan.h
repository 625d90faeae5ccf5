// The straight chords a camera ray's walk tests against the scene, planned once per
// ElevationTable entry instead of per pixel. Consecutive path nodes are joined into one chord
// while every node and segment quarter point between them lies within the tolerance of it; a
// segment that itself strays further is cut into pieces. No chord reaches across a node where the
// path turns up or down, so the chords of the entry's own path cross every level it crosses (a
// grazing path that dips under the sea and rises again within the tolerance still meets the sea).
// Every pixel whose path interpolates that entry (its nodes correspond one to one) walks the same
// plan; its own turn may lie a node from the entry's, within one chord's stray.
#pragma once

#include "refracta/rays/ray_path.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace refracta {

struct PlannedChord {
  uint32_t first, last;  // path nodes joined by the chord
  uint32_t pieces;       // > 1: one segment (last = first + 1) cut into this many chords
};
using ChordPlan = std::vector<PlannedChord>;

// tolerance(s): the largest distance [m] a chord starting at arc length s may stray from the
// path; max_chord [m]: the longest chord.
ChordPlan plan_chords(const RayPath& path, const std::function<double(double)>& tolerance, double max_chord);

}  // namespace refracta
