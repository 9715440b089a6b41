# IBS_FUZZ: every target of the build is compiled for libFuzzer (coverage instrumentation without
# libFuzzer's main) under AddressSanitizer and UndefinedBehaviorSanitizer, and undefined behaviour
# aborts instead of being reported and passed over. fuzz/CMakeLists.txt links its targets with
# -fsanitize=fuzzer (ibs_add_fuzzer). Included from the root before any library is defined.
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "IBS_FUZZ needs clang (libFuzzer); this is ${CMAKE_CXX_COMPILER_ID}. "
                      "Use the preset: cmake --preset fuzz")
endif()

set(IBS_FUZZ_SANITIZERS address,undefined)
add_compile_options(-fsanitize=fuzzer-no-link,${IBS_FUZZ_SANITIZERS} -fno-sanitize-recover=all
                    -fno-omit-frame-pointer)
add_link_options(-fsanitize=${IBS_FUZZ_SANITIZERS})
