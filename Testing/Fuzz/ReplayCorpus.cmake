# ctest FuzzCorpusReplay: runs each fuzz target's replay executable (-D<target>=path)
# over Testing/Fuzz/corpus/<target>/ and Testing/Fuzz/crashes/<target>/, every
# input once. A crash, a sanitizer report or a failed check of the target fails it and
# names the input (the replay prints each name before running it).
set(failed)
foreach (target IN LISTS TARGETS)
  execute_process(
    COMMAND "${${target}}" "${FUZZ_DIR}/corpus/${target}" "${FUZZ_DIR}/crashes/${target}"
    RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE errors)
  string(REGEX MATCH "replayed [0-9]+ inputs in [0-9.]+ s" summary "${output}")
  if (NOT result EQUAL 0)
    string(REGEX MATCH "replay: [^\n]*\n$" last "${output}")
    string(LENGTH "${errors}" length)
    if (length GREATER 4000)
      math(EXPR from "${length} - 4000")
      string(SUBSTRING "${errors}" ${from} 4000 errors)
    endif ()
    message("${target}: exit ${result} on the last input: ${last}${errors}")
    list(APPEND failed ${target})
  else ()
    message("${target}: ${summary}")
  endif ()
endforeach ()
if (failed)
  message(FATAL_ERROR "corpus replay: FAILED (${failed})")
endif ()
message("corpus replay: ok")
