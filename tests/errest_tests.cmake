# Error estimates of steady results and grid.accuracy (study/errest.h, issue 44).
# (Included by tests/CMakeLists.txt.)
rs_unit_test(test_errest)
set_tests_properties(test_errest PROPERTIES TIMEOUT 120)
