# Runs an example program and compares its standard output with the file the documentation
# shows (doc/output/<example>.txt, written by scripts/examples.sh):
#   cmake -D EXE=<program> -D EXPECTED=<file> [-D ARGS=<a;b>] -P fsym_compare_output.cmake
# (ARGS: the program's command-line arguments, if any; it runs in the current directory)
# Fails on a non-zero exit or any difference (and prints both texts).
foreach(var EXE EXPECTED)
    if(NOT DEFINED ${var})
        message(FATAL_ERROR "fsym_compare_output.cmake: ${var} not set")
    endif()
endforeach()
execute_process(COMMAND "${EXE}" ${ARGS} OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${EXE} exited with ${rc}: ${err}")
endif()
file(READ "${EXPECTED}" expected)
if(NOT out STREQUAL expected)
    message(FATAL_ERROR "the output of ${EXE} differs from ${EXPECTED} "
                        "(bash scripts/examples.sh rewrites it):\n--- now:\n${out}"
                        "--- documented:\n${expected}")
endif()
message(STATUS "output as documented in ${EXPECTED}")
