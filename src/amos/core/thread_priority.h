#pragma once
// Scheduling weight of background threads. On 2 cores the work that sets a frame's latency (stage B, the frame and
// partition lanes) shares the CPU with work that has slack: the person network (its masks are used `lag` frames
// later) and local mapping (keyframes queue). Giving the latter a lower weight (a higher nice value, which Linux
// applies per thread) lets the latency-critical threads run first when both are ready, without starving the
// background ones: at nice +10 a thread still gets a tenth of a core's time against a busy nice-0 thread, and all
// of the time the frame threads leave (a live run at 30 Hz leaves about a third of the two cores). Why +10 and not
// +5: docs/performance.md ("Background threads at nice +10").
namespace amos::core {

// Nice increment of background threads (segmentation lane, local mapping, dense fusion, the viewer's recorder and
// publisher).
inline constexpr int kBackgroundNice = 10;

// Adds `increment` to the calling thread's nice value (Linux: per thread). Best effort: returns false and changes
// nothing where the system does not allow it.
bool lowerThisThreadPriority(int increment);

}  // namespace amos::core
