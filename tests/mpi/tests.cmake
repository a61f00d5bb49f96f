strand_test(NAME mpi_parallel_agreement SOURCES mpi/test_parallel_agreement.cpp LABELS mpi NPROCS 1 2)
