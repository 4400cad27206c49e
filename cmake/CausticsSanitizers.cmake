# CAUSTICS_SANITIZE: builds everything (the modules, tools and tests) with
# AddressSanitizer and UndefinedBehaviorSanitizer, for scripts/sanitize.sh.
# Undefined behaviour stops the program (-fno-sanitize-recover) so that a test
# fails on it instead of printing and passing. VTK, Mesa and the other system
# libraries are not instrumented; what they leak is suppressed in
# Testing/Sanitizers/lsan.supp.
option(CAUSTICS_SANITIZE "Build with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
if (CAUSTICS_SANITIZE)
  if (NOT CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    message(FATAL_ERROR "CAUSTICS_SANITIZE needs GCC or Clang, not ${CMAKE_CXX_COMPILER_ID}")
  endif ()
  set(caustics_sanitize_flags -fsanitize=address,undefined -fno-sanitize-recover=undefined
    -fno-omit-frame-pointer)
  add_compile_options(${caustics_sanitize_flags})
  add_link_options(${caustics_sanitize_flags})
endif ()
