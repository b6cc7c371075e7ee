#pragma once
// The project builds for baseline x86-64, where __builtin_popcountll becomes a slow library call. Hot
// bit-counting functions are therefore marked AMOS_POPCNT_CLONES: compiled twice, with and without the POPCNT
// instruction, and the loader picks the right one for the CPU (GCC/Clang function multi-versioning).
// Not under ThreadSanitizer: the loader runs the clones' resolver before the TSan runtime exists, and GCC
// instruments the resolver, so the program crashed at load.
#if defined(__SANITIZE_THREAD__)
#define AMOS_POPCNT_CLONES
#elif defined(__x86_64__) && defined(__linux__) && (defined(__GNUC__) || defined(__clang__))
#define AMOS_POPCNT_CLONES __attribute__((target_clones("popcnt", "default")))
#else
#define AMOS_POPCNT_CLONES
#endif
