strand_test(NAME unit_math SOURCES unit/test_math.cpp LABELS unit)
strand_test(NAME unit_ancf_cable SOURCES unit/test_ancf_cable.cpp LABELS unit)
