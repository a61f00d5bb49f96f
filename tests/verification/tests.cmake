# verification tests
