# The fuzz build (KELVIN_FUZZ=ON, the `fuzz` preset): clang, every object
# compiled with libFuzzer's coverage instrumentation, AddressSanitizer and
# UBSan; every sanitizer report aborts, so libFuzzer records it as a crash.
if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR "KELVIN_FUZZ needs clang (cmake --preset fuzz uses clang++-14); found ${CMAKE_CXX_COMPILER_ID}")
endif()
# Sections per function and per datum let the linker drop what the readers
# never reach (and the references it makes to the rest of the solver).
add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
  -ffunction-sections -fdata-sections)
add_link_options(-fsanitize=address,undefined -Wl,--gc-sections)
