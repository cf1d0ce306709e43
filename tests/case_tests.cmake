# Case-file module: histories, valid cases, and one test per malformed case file.
# (Included by tests/CMakeLists.txt; RS_TESTS is the tests source directory.)

# A test program linked against librollsim whose ctest runs get arguments.
function(rs_case_test_program name)
  add_executable(${name} ${RS_TESTS}/${name}.c)
  target_link_libraries(${name} PRIVATE rollsim_lib)
endfunction()

rs_case_test_program(test_history)
add_test(NAME case_history COMMAND test_history)

rs_case_test_program(test_case_good)
add_test(NAME case_good_inputs
  COMMAND test_case_good ${RS_TESTS}/good_inputs ${CMAKE_CURRENT_BINARY_DIR})

# Each tests/bad_inputs/*.yaml says on its first lines what the message must name.
rs_case_test_program(test_case_bad)
file(GLOB RS_BAD_CASES CONFIGURE_DEPENDS ${RS_TESTS}/bad_inputs/*.yaml)
foreach(bad ${RS_BAD_CASES})
  get_filename_component(stem ${bad} NAME_WE)
  add_test(NAME case_bad_${stem} COMMAND test_case_bad ${bad})
endforeach()
