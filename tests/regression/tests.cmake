# regression tests
