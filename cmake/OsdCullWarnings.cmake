include_guard(GLOBAL)
# osd_cull_warnings(target): our warning set; errors when OSD_CULL_WERROR is on (CI).
function(osd_cull_warnings target)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow
      -Wno-missing-field-initializers)
    if(OSD_CULL_WERROR)
      target_compile_options(${target} PRIVATE -Werror)
    endif()
  endif()
endfunction()
