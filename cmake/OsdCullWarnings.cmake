include_guard(GLOBAL)
# osd_cull_warnings(target): our warning set; errors when OSD_CULL_WERROR is on (CI).
function(osd_cull_warnings target)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow
      -Wno-missing-field-initializers)
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
      # GCC 12 at -O3 reports impossible std::string overlaps in operator+ (-Wrestrict
      # false positive, GCC bug 105329); the code is fine, the warning is not.
      target_compile_options(${target} PRIVATE -Wno-restrict)
    endif()
    if(OSD_CULL_WERROR)
      target_compile_options(${target} PRIVATE -Werror)
    endif()
  endif()
endfunction()
