strand_test(NAME regression_cli SOURCES regression/test_cli.cpp LABELS regression)
target_compile_definitions(regression_cli PRIVATE STRAND_MPIEXEC="${MPIEXEC_EXECUTABLE}")
strand_test(NAME regression_reliability SOURCES regression/test_reliability.cpp LABELS regression)
target_compile_definitions(regression_reliability PRIVATE STRAND_MPIEXEC="${MPIEXEC_EXECUTABLE}")
