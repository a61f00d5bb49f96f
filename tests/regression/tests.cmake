strand_test(NAME regression_cli SOURCES regression/test_cli.cpp LABELS regression)
target_compile_definitions(regression_cli PRIVATE STRAND_MPIEXEC="${MPIEXEC_EXECUTABLE}")
strand_test(NAME regression_reliability SOURCES regression/test_reliability.cpp LABELS regression)
target_compile_definitions(regression_reliability PRIVATE STRAND_MPIEXEC="${MPIEXEC_EXECUTABLE}")
# issue 32 item 4: kill -9 at random moments, every output readable (tests/regression/kill_test.py).
# A short version in the default suite; kill_test_long (400 kills, about 8 minutes) on demand.
add_test(NAME regression_kill COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/regression/kill_test.py
         $<TARGET_FILE:strand_cli> --kills 30 --max-delay 1.2)
set_tests_properties(regression_kill PROPERTIES LABELS regression SKIP_RETURN_CODE 77 TIMEOUT 300)
add_custom_target(kill_test_long COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/regression/kill_test.py
                  $<TARGET_FILE:strand_cli> --kills 400 --max-delay 2.0 DEPENDS strand_cli USES_TERMINAL)
