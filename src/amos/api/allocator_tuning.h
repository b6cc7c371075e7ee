#pragma once
// glibc's allocator tuned for the library's per-frame buffers (Options::tune_allocator, include/amos/slam.h).
namespace amos::api {

// Raises glibc's mmap threshold to 32 MiB and its trim threshold to 512 MiB (also what `amos-slam`'s main() calls):
// the per-frame buffers (images, pyramids, network blobs) are megabytes, above glibc's default thresholds,
// so each would be mapped and unmapped again every frame (page faults: about a tenth of a Bonn run's CPU time).
// Process-wide; done once, by the first call. Nothing on other C libraries.
void tuneAllocatorOnce();

}  // namespace amos::api
