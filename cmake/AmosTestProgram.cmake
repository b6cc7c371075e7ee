# amos_test_program_options(<test target>)
# Test programs are compiled at -O1 in an optimised build: their code is assertions and set-up, and GCC spends
# about 30 % less time on a unity test file at -O1 than at -O3 (the test command compiles ~35 of them on a fresh
# machine). The libraries they test keep the build type's flags; the same results follow, since no file is built
# with -ffast-math or -march flags that would let the two levels round differently.
function(amos_test_program_options target)
  target_compile_options(${target} PRIVATE $<$<CONFIG:Release,RelWithDebInfo>:-O1>)
endfunction()
