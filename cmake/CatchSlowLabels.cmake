# Post-build step of dpcr_catch_tests (tests/CMakeLists.txt): writes the ctest commands that add
# the label "slow" to the test cases tagged [slow]. Catch2 2.x's discovery gives every case of a
# binary the same labels, so the tag is read here from the binary itself.
# Usage: cmake -DEXECUTABLE=<test binary> -DEMULATOR=<cross emulator or ""> -DPREFIX=<ctest prefix>
#              -DLABELS=<the binary's labels, comma-separated> -DOUTPUT=<file> -P CatchSlowLabels.cmake
execute_process(COMMAND ${EMULATOR} ${EXECUTABLE} [slow] --list-test-names-only
                OUTPUT_VARIABLE names RESULT_VARIABLE rc)
# Catch exits with the number of cases listed; anything else means the binary did not run.
if(NOT rc MATCHES "^[0-9]+$")
  message(FATAL_ERROR "${EXECUTABLE} [slow] --list-test-names-only: ${rc}")
endif()
string(REPLACE "," ";" labels "${LABELS}")
list(APPEND labels slow)
string(REPLACE "\n" ";" names "${names}")
set(script "")
foreach(name IN LISTS names)
  if(NOT name STREQUAL "")
    string(APPEND script "set_tests_properties([==[${PREFIX}${name}]==] PROPERTIES LABELS [==[${labels}]==])\n")
  endif()
endforeach()
file(WRITE ${OUTPUT} "${script}")
