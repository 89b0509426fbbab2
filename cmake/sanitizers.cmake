# Sanitizer and fuzzing builds.
#   -DLIGSIM_SANITIZE=ON: AddressSanitizer + UndefinedBehaviorSanitizer on everything we compile
#     (gcc or clang); any UB report aborts the test that triggered it.
#   -DLIGSIM_FUZZ=ON (clang only): the libFuzzer targets of tests/fuzz are linked with
#     -fsanitize=fuzzer; without it they are built with a replay driver that runs the seed
#     corpus and deterministic mutations of it (a short run in the normal suite).
option(LIGSIM_SANITIZE "Build with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
option(LIGSIM_FUZZ "Link the tests/fuzz targets with libFuzzer (clang)" OFF)

if(LIGSIM_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=undefined
                      -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()

if(LIGSIM_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "LIGSIM_FUZZ needs clang (libFuzzer): configure with "
                        "-DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_C_COMPILER=clang-14")
  endif()
  # Coverage instrumentation for everything the fuzz targets link.
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
