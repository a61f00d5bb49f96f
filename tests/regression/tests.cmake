strand_test(NAME regression_cli SOURCES regression/test_cli.cpp LABELS regression)
