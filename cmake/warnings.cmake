# ibs_set_warnings(target): the project's warning set, errors when IBS_WERROR is on.
# The set is GCC's; the options clang does not know are given to GCC only, so that a clang build
# (the `fuzz` preset) is as warning-free as the GCC one.
function(ibs_set_warnings target)
  target_compile_options(${target} PRIVATE
    -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion
    -Wnon-virtual-dtor -Wold-style-cast -Woverloaded-virtual
    -Wdouble-promotion -Wformat=2 -Wimplicit-fallthrough -Wmisleading-indentation)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE
      -Wduplicated-cond -Wlogical-op -Wuseless-cast
      # GCC 12 at -O2/-O3 reports -Wrestrict and -Wnull-dereference inside libstdc++'s own
      # std::string and streambuf code (GCC bugs 105329, 105651): false positives we cannot fix.
      -Wno-restrict)
  endif()
  if(IBS_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
