#pragma once
// Timestamp association exactly as the TUM RGB-D benchmark's associate.py: candidates are all (a, b) with
// |a - (b + offset)| < max_difference (strict), taken greedily in order of increasing difference (ties: smaller a,
// then smaller b, as Python sorts the tuples), each stamp used at most once; the matches are returned sorted by a.
// Used for RGB-depth pairs (io) and for ground-truth / estimate pairs (eval).
#include <cstddef>
#include <utility>
#include <vector>

namespace amos::io {

// Index pairs (i into first, j into second). Inputs need not be sorted. O((n + m) log + candidates).
std::vector<std::pair<std::size_t, std::size_t>> associateStamps(const std::vector<double>& first,
                                                                 const std::vector<double>& second,
                                                                 double max_difference, double offset = 0.0);

}  // namespace amos::io
