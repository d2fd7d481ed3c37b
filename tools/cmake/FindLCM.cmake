# FindLCM: Debian's LCM 1.3.1 ships no CMake config, only lcm.pc (which pulls
# in glib). Defines LCM::lcm and LCM_GEN_EXECUTABLE, and the function
# lcm_generate_cpp(<target> <out_dir> <files...>) that runs lcm-gen at build time.
find_package(PkgConfig REQUIRED)
pkg_check_modules(PC_LCM QUIET IMPORTED_TARGET lcm)
find_path(LCM_INCLUDE_DIR lcm/lcm-cpp.hpp HINTS ${PC_LCM_INCLUDE_DIRS})
find_library(LCM_LIBRARY lcm HINTS ${PC_LCM_LIBRARY_DIRS})
find_program(LCM_GEN_EXECUTABLE lcm-gen)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(LCM REQUIRED_VARS LCM_LIBRARY LCM_INCLUDE_DIR LCM_GEN_EXECUTABLE
  VERSION_VAR PC_LCM_VERSION)

if(LCM_FOUND AND NOT TARGET LCM::lcm)
  add_library(LCM::lcm INTERFACE IMPORTED)
  if(TARGET PkgConfig::PC_LCM)
    target_link_libraries(LCM::lcm INTERFACE PkgConfig::PC_LCM)
  else()
    target_include_directories(LCM::lcm INTERFACE ${LCM_INCLUDE_DIR})
    target_link_libraries(LCM::lcm INTERFACE ${LCM_LIBRARY})
  endif()
endif()

# lcm_generate_cpp(<target> <out_dir> <lcm files...>): C++ headers from .lcm
# definitions, regenerated when a definition changes. --cpp-std=c++11 makes
# the message constants constexpr (usable at namespace scope and in switch).
# The generated code uses C-style casts: include <out_dir> as a SYSTEM
# directory in targets built with the project warnings.
function(lcm_generate_cpp target out_dir)
  set(headers)
  foreach(def ${ARGN})
    get_filename_component(abs ${def} ABSOLUTE)
    file(STRINGS ${abs} pkg_line REGEX "^package ")
    string(REGEX REPLACE "^package[ \t]+([A-Za-z0-9_]+).*" "\\1" pkg "${pkg_line}")
    get_filename_component(stem ${def} NAME_WE)
    set(hdr ${out_dir}/${pkg}/${stem}.hpp)
    add_custom_command(OUTPUT ${hdr}
      COMMAND ${LCM_GEN_EXECUTABLE} --cpp --cpp-std=c++11 --cpp-hpath ${out_dir} ${abs}
      DEPENDS ${abs}
      COMMENT "lcm-gen ${stem}.lcm"
      VERBATIM)
    list(APPEND headers ${hdr})
  endforeach()
  add_custom_target(${target} DEPENDS ${headers})
endfunction()
