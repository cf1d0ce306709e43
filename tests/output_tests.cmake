# netCDF output (src/io/output.c): round trip through the C API, errors, a check with the
# Python reader post-processing uses, ncdump, and crash safety under SIGKILL.
# Included from tests/CMakeLists.txt (rs_unit_test, RS_TESTS, SYSTEM_PYTHON3).

rs_unit_test(test_output_roundtrip)
rs_unit_test(test_output_errors)

# Writes records with known values (see its header); used by the checks below.
add_executable(test_output_crash_writer ${RS_TESTS}/test_output_crash_writer.c)
target_link_libraries(test_output_crash_writer PRIVATE rollsim_lib)

# One file (20 records, 13 cells, status complete) read by Python and by ncdump.
set(RS_OUTPUT_CHECK_FILE ${CMAKE_CURRENT_BINARY_DIR}/test_output_check.nc)
add_test(NAME test_output_check_write
  COMMAND test_output_crash_writer ${RS_OUTPUT_CHECK_FILE} 20 0 13)
set_tests_properties(test_output_check_write PROPERTIES FIXTURES_SETUP rs_output_check_file)

add_test(NAME test_output_python
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_output.py ${RS_OUTPUT_CHECK_FILE} 20)
set_tests_properties(test_output_python PROPERTIES FIXTURES_REQUIRED rs_output_check_file)

# 24 writers killed with SIGKILL at random moments; a few seconds in all.
add_test(NAME test_output_crash
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_output_crash.py
    $<TARGET_FILE:test_output_crash_writer> ${CMAKE_CURRENT_BINARY_DIR}/test_output_crash.d 24)
set_tests_properties(test_output_crash PROPERTIES TIMEOUT 60)

find_program(RS_NCDUMP ncdump)
if(RS_NCDUMP)
  # One pattern, in header order ('.' matches newlines in CMake regexes; no ';' in it,
  # which would split it into a list of alternatives).
  string(CONCAT RS_NCDUMP_EXPECTED
    "time = UNLIMITED . // \\(20 currently\\).*x = 13 "
    ".*regime:flag_values = 0b, 1b, 2b, 3b "
    ".*regime:flag_meanings = \"exterior adhesion slip plastic\" "
    ".*Fx:units = \"N/mm\" "
    ".*:Conventions = \"CF-1.10\" "
    ".*:status = \"complete\" ")
  add_test(NAME test_output_ncdump COMMAND ${RS_NCDUMP} -h ${RS_OUTPUT_CHECK_FILE})
  set_tests_properties(test_output_ncdump PROPERTIES
    FIXTURES_REQUIRED rs_output_check_file
    PASS_REGULAR_EXPRESSION "${RS_NCDUMP_EXPECTED}")
else()
  add_test(NAME test_output_ncdump COMMAND ncdump -h ${RS_OUTPUT_CHECK_FILE})
  set_tests_properties(test_output_ncdump PROPERTIES DISABLED TRUE)
  message(STATUS "output tests: ncdump not found, test_output_ncdump disabled")
endif()
