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
  # Mesa's driver stays mapped until exit, or LeakSanitizer reports what it holds
  # from an unnamed module (Testing/Sanitizers/KeepGLDriverLoaded.cxx says why).
  find_file(CAUSTICS_SANITIZE_GL_DRIVER swrast_dri.so
    PATHS /usr/lib/x86_64-linux-gnu/dri /usr/lib64/dri /usr/lib/dri NO_DEFAULT_PATH
    DOC "Mesa driver kept loaded until exit in sanitizer builds")
  if (CAUSTICS_SANITIZE_GL_DRIVER)
    # Compiled once at configure time and put on every link line, executables and
    # libraries alike, without becoming a target the modules' export sets would need.
    set(keep_object "${CMAKE_BINARY_DIR}/CMakeFiles/caustics_keep_gl_driver.o")
    execute_process(
      COMMAND "${CMAKE_CXX_COMPILER}" -std=c++17 -fPIC -O1 -c
        "-DCAUSTICS_SANITIZE_GL_DRIVERS=\"${CAUSTICS_SANITIZE_GL_DRIVER}\""
        "${CMAKE_CURRENT_LIST_DIR}/../Testing/Sanitizers/KeepGLDriverLoaded.cxx" -o "${keep_object}"
      RESULT_VARIABLE keep_result ERROR_VARIABLE keep_error)
    if (NOT keep_result EQUAL 0)
      message(FATAL_ERROR "CAUSTICS_SANITIZE: cannot compile KeepGLDriverLoaded.cxx: ${keep_error}")
    endif ()
    string(APPEND CMAKE_CXX_STANDARD_LIBRARIES " ${keep_object} -ldl")
  endif ()
endif ()
