# ibs_set_warnings(target): the project's warning set, errors when IBS_WERROR is on.
function(ibs_set_warnings target)
  target_compile_options(${target} PRIVATE
    -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion
    -Wnon-virtual-dtor -Wold-style-cast -Woverloaded-virtual
    -Wdouble-promotion -Wformat=2 -Wimplicit-fallthrough -Wmisleading-indentation
    -Wduplicated-cond -Wlogical-op -Wuseless-cast
    # GCC 12 at -O2/-O3 reports -Wrestrict and -Wnull-dereference inside libstdc++'s own
    # std::string and streambuf code (GCC bugs 105329, 105651): false positives we cannot fix.
    -Wno-restrict)
  if(IBS_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
