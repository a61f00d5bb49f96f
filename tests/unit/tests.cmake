strand_test(NAME unit_math SOURCES unit/test_math.cpp LABELS unit)
strand_test(NAME unit_ancf_cable SOURCES unit/test_ancf_cable.cpp LABELS unit)
strand_test(NAME unit_elastica_reference SOURCES unit/test_elastica_reference.cpp LABELS unit)
