# Installs the build into a temporary prefix and uses it from outside, as a user
# would (see CMakeLists.txt here). cmake -P with BUILD_DIR, SOURCE_DIR, WORK,
# GENERATOR, BUILD_TYPE, CXX_COMPILER, CXX_LAUNCHER (may be empty), PYTHON (empty
# without the wrapping) and READELF. Prints "install: ok" when every step passed.
cmake_minimum_required(VERSION 3.16)

string(TIMESTAMP caustics_start "%s")
function (caustics_step message)
  string(TIMESTAMP now "%s")
  math(EXPR elapsed "${now} - ${caustics_start}")
  message(STATUS "[${elapsed} s] ${message}")
endfunction ()

# caustics_run(<what> <expected regex> COMMAND ...): runs the command, fails with
# its output unless it exits 0 and its output matches the regex.
function (caustics_run what expected)
  cmake_parse_arguments(PARSE_ARGV 2 run "" "WORKING_DIRECTORY" "COMMAND")
  if (NOT run_WORKING_DIRECTORY)
    set(run_WORKING_DIRECTORY "${WORK}")
  endif ()
  execute_process(COMMAND ${run_COMMAND}
    WORKING_DIRECTORY "${run_WORKING_DIRECTORY}"
    RESULT_VARIABLE code OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if (NOT code EQUAL 0 OR NOT output MATCHES "${expected}")
    message(FATAL_ERROR "${what} failed (exit ${code}):\n${output}")
  endif ()
  caustics_step("${what}")
  set(caustics_output "${output}" PARENT_SCOPE)
endfunction ()

# 1. Install, then move the prefix: nothing may depend on where it was installed.
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(staged "${WORK}/staged-prefix")
set(prefix "${WORK}/prefix")
caustics_run("cmake --install into ${staged}" ""
  COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${staged}")
file(RENAME "${staged}" "${prefix}")
foreach (expected
    lib/cmake/vtkcaustics/VTKCausticsConfig.cmake
    lib/cmake/vtkcaustics/VTKCausticsConfigVersion.cmake
    share/vtkcaustics/data/bunny.ply
    share/vtkcaustics/scripts/plot-benchmarks.py
    bin/caustics-render bin/caustics-view bin/caustics-bench bin/caustics-ceilings)
  if (NOT EXISTS "${prefix}/${expected}")
    message(FATAL_ERROR "the installed prefix has no ${expected}")
  endif ()
endforeach ()
if (PYTHON)
  foreach (expected
      lib/python3/dist-packages/vtkcaustics/__init__.py
      share/vtkcaustics/examples/render_ball_lens.py)
    if (NOT EXISTS "${prefix}/${expected}")
      message(FATAL_ERROR "the installed prefix has no ${expected}")
    endif ()
  endforeach ()
endif ()

# 2. No installed file names the source tree, the build tree or the staging prefix,
#    and every run path is relative to the file ($ORIGIN).
set(forbidden)
foreach (folder IN ITEMS "${SOURCE_DIR}" "${BUILD_DIR}" "${staged}")
  string(REGEX REPLACE "([][+.*()^$?|\\\\])" "\\\\\\1" folder "${folder}")
  list(APPEND forbidden "${folder}")
endforeach ()
list(JOIN forbidden "|" forbidden)
file(GLOB_RECURSE installed LIST_DIRECTORIES false "${prefix}/*")
foreach (file IN LISTS installed)
  file(STRINGS "${file}" named REGEX "${forbidden}")
  if (named)
    list(GET named 0 line)
    message(FATAL_ERROR "${file} names the build or source folder: ${line}")
  endif ()
  execute_process(COMMAND "${READELF}" -d "${file}"
    RESULT_VARIABLE not_elf OUTPUT_VARIABLE dynamic ERROR_QUIET)
  if (not_elf EQUAL 0)
    string(REGEX MATCHALL "R(UN)?PATH\\)[^\n]*\\[[^]\n]*\\]" paths "${dynamic}")
    foreach (path IN LISTS paths)
      string(REGEX REPLACE ".*\\[(.*)\\]" "\\1" path "${path}")
      string(REPLACE ":" ";" entries "${path}")
      foreach (entry IN LISTS entries)
        if (NOT entry MATCHES "^\\$ORIGIN")
          message(FATAL_ERROR "${file} has the run path ${entry}, not relative to $ORIGIN")
        endif ()
      endforeach ()
    endforeach ()
  endif ()
endforeach ()
list(LENGTH installed count)
caustics_step("${count} installed files name no build or source folder; run paths use $ORIGIN")

# 3. A project of its own finds the package in the moved prefix (and nowhere else),
#    builds and runs.
set(consumer_build "${WORK}/consumer-build")
set(launcher)
if (CXX_LAUNCHER)
  set(launcher "-DCMAKE_CXX_COMPILER_LAUNCHER=${CXX_LAUNCHER}")
endif ()
caustics_run("configure the consumer project" "VTKCaustics 0[.]1[.][0-9]+ from"
  COMMAND "${CMAKE_COMMAND}" -S "${CMAKE_CURRENT_LIST_DIR}/Consumer" -B "${consumer_build}"
          -G "${GENERATOR}" "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}"
          "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" ${launcher}
          "-DCMAKE_PREFIX_PATH=${prefix}" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
file(STRINGS "${consumer_build}/CMakeCache.txt" found_at REGEX "^VTKCaustics_DIR:")
if (NOT found_at STREQUAL "VTKCaustics_DIR:PATH=${prefix}/lib/cmake/vtkcaustics")
  message(FATAL_ERROR "the consumer found VTKCaustics elsewhere: ${found_at}")
endif ()
caustics_run("build the consumer project" ""
  COMMAND "${CMAKE_COMMAND}" --build "${consumer_build}")
caustics_run("run the consumer" "consumer: ok"
  COMMAND "${consumer_build}/caustics-consumer" "${WORK}/consumer")
message("${caustics_output}")

# 4. The installed command line runs from elsewhere and finds its data (bunny.ply).
caustics_run("run the installed caustics-render" "wrote .*installed-cli-bunny.png"
  COMMAND "${prefix}/bin/caustics-render" bunny --size 32 --photons 16
          --output "${WORK}/installed-cli-bunny")

# 5. The installed Python package, with only the prefix on PYTHONPATH, and the
#    installed example rendering headless (no DISPLAY: EGL).
if (PYTHON)
  caustics_run("import vtkcaustics from the prefix" "consumer.py: ok"
    COMMAND "${CMAKE_COMMAND}" -E env "PYTHONPATH=${prefix}/lib/python3/dist-packages"
            "${PYTHON}" "${CMAKE_CURRENT_LIST_DIR}/Consumer/consumer.py" "${prefix}")
  message("${caustics_output}")
  caustics_run("run the installed Python example with no X server" "window egl-.*wrote"
    COMMAND "${CMAKE_COMMAND}" -E env --unset=DISPLAY
            "PYTHONPATH=${prefix}/lib/python3/dist-packages" "${PYTHON}"
            "${prefix}/share/vtkcaustics/examples/render_ball_lens.py" --size 64
            --output "${WORK}/installed-example")
endif ()

caustics_step("install: ok")
