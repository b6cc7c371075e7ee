#pragma once
// The project builds for baseline x86-64, where __builtin_popcountll becomes a slow library call. Hot
// bit-counting functions are therefore marked AMOS_POPCNT_CLONES: compiled twice, with and without the POPCNT
// instruction, and the loader picks the right one for the CPU (GCC/Clang function multi-versioning).
#if defined(__x86_64__) && defined(__linux__) && (defined(__GNUC__) || defined(__clang__))
#define AMOS_POPCNT_CLONES __attribute__((target_clones("popcnt", "default")))
#else
#define AMOS_POPCNT_CLONES
#endif
