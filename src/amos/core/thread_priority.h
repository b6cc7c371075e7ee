#pragma once
// Scheduling weight of background threads. On 2 cores the work that sets a frame's latency (stage B, the frame and
// partition lanes) shares the CPU with work that has slack: the person network (its masks are used `lag` frames
// later) and local mapping (keyframes queue). Giving the latter a lower weight (a higher nice value, which Linux
// applies per thread) lets the latency-critical threads run first when both are ready, without starving the
// background ones: at nice +5 a thread still gets a quarter of a core's time against a busy nice-0 thread.
namespace amos::core {

// Nice increment of background threads (segmentation lane, local mapping).
inline constexpr int kBackgroundNice = 5;

// Adds `increment` to the calling thread's nice value (Linux: per thread). Best effort: returns false and changes
// nothing where the system does not allow it.
bool lowerThisThreadPriority(int increment);

}  // namespace amos::core
