strand_test(NAME verify_cantilever_statics SOURCES verification/test_cantilever_statics.cpp LABELS verification)
strand_test(NAME verify_cantilever_modes SOURCES verification/test_cantilever_modes.cpp LABELS verification NPROCS 1 2)
strand_test(NAME verify_mass_properties SOURCES verification/test_mass_properties.cpp LABELS verification NPROCS 1 2)
strand_test(NAME verify_rotating_modes SOURCES verification/test_rotating_modes.cpp LABELS verification NPROCS 1 2)
