#include "amos/io/frame_source.h"

#include <numeric>

namespace amos::io {

const char* frameProblemName(FrameProblem problem) {
  switch (problem) {
    case FrameProblem::kMissing: return "missing";
    case FrameProblem::kUnreadable: return "unreadable";
    case FrameProblem::kWrongSize: return "wrong_size";
    case FrameProblem::kWrongFormat: return "wrong_format";
    case FrameProblem::kBlank: return "blank";
  }
  return "?";
}

std::size_t SkippedFrames::total() const { return std::accumulate(by_problem.begin(), by_problem.end(), std::size_t{0}); }

}  // namespace amos::io
