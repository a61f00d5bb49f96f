strand_test(NAME regression_cli SOURCES regression/test_cli.cpp LABELS regression)
target_compile_definitions(regression_cli PRIVATE STRAND_MPIEXEC="${MPIEXEC_EXECUTABLE}")
