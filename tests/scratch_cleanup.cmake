# Runs tests that write scratch files (no_skip_main.cpp, test_files.hpp) with TMPDIR an
# empty folder: after they pass, the folder must be empty again; a test run must not
# leave its files in the machine's temporary folder.
# cmake -DTESTS=<lccp_tests> -DTMP=<folder> -P scratch_cleanup.cmake
file(REMOVE_RECURSE "${TMP}")
file(MAKE_DIRECTORY "${TMP}")
execute_process(COMMAND "${CMAKE_COMMAND}" -E env "TMPDIR=${TMP}" "${TESTS}"
                        "--gtest_filter=AtomicFile.*:IoWrite.*:CliTest.MissingInputFile:CliTest.TruncatedPcd"
                RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the tests failed (exit ${status}):\n${output}")
endif()
if(NOT output MATCHES "PASSED  \\] [1-9][0-9]* tests")
  message(FATAL_ERROR "no test ran:\n${output}")
endif()
file(GLOB_RECURSE left LIST_DIRECTORIES true "${TMP}/*")
if(left)
  message(FATAL_ERROR "a passing run left files in the temporary folder: ${left}")
endif()
file(REMOVE_RECURSE "${TMP}")
