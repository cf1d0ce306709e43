# The Python package postproc/rollsim over librollsim.so (issue 16): every shipped case run
# in-process equals the command line's file bit for bit, a sweep with set=, dict cases, two
# runs in one process, CaseError with the command line's messages (tests/check_python.py);
# and the package installed by pip from the repository, found through ROLLSIM_LIB.
# Not in sanitizer builds: an instrumented librollsim.so cannot be loaded into an uninstrumented
# Python (the ASan runtime must come first); the ordinary build runs these.
if(CMAKE_C_FLAGS MATCHES "sanitize")
  return()
endif()
file(GLOB RS_PY_CASES CONFIGURE_DEPENDS ${RS_CASES}/*.yaml)
set(RS_PY_WORK ${CMAKE_CURRENT_BINARY_DIR}/python)
add_test(NAME py_api_cases
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_python.py ${RS_BIN} ${RS_PY_WORK}/cases ${RS_PY_CASES})
set_tests_properties(py_api_cases PROPERTIES TIMEOUT 600
  ENVIRONMENT "ROLLSIM_LIB=$<TARGET_FILE:rollsim_shared>")
add_test(NAME py_pip_install
  COMMAND sh -c "rm -rf '${RS_PY_WORK}/pip' && mkdir -p '${RS_PY_WORK}/pip' && cp -r '${PROJECT_SOURCE_DIR}/postproc' '${RS_PY_WORK}/pip/src' && rm -rf '${RS_PY_WORK}/pip/src/build' && ${SYSTEM_PYTHON3} -m pip install -q --no-build-isolation --no-index --target '${RS_PY_WORK}/pip/site' '${RS_PY_WORK}/pip/src' && cd / && PYTHONPATH='${RS_PY_WORK}/pip/site' ROLLSIM_LIB='$<TARGET_FILE:rollsim_shared>' ${SYSTEM_PYTHON3} -c \"import rollsim, os; assert rollsim.__file__.startswith('${RS_PY_WORK}/pip/site'), rollsim.__file__; ds = rollsim.run('${RS_CASES}/carter2d.yaml'); f = float(ds.Fx[0] / ds.Fn[0]); print('F_x/F_n', f); assert abs(f / 0.3 - 0.64) < 0.01\"")
set_tests_properties(py_pip_install PROPERTIES ENVIRONMENT "PIP_ROOT_USER_ACTION=ignore")
# set= as a dict or a list of "KEY=VALUE" strings; anything else a TypeError saying so.
add_test(NAME py_api_set COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_python_set.py ${RS_CASES})
set_tests_properties(py_api_set PROPERTIES ENVIRONMENT "ROLLSIM_LIB=$<TARGET_FILE:rollsim_shared>")
# rollsim.sweep on profiles (a path of wheelset positions) equals the command line's file bit for
# bit; rollsim.run on profiles points to the command line.
add_test(NAME py_api_profiles
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_python_profiles.py ${RS_BIN}
    ${RS_CASES}/profiles/mbench_a22_right.yaml ${RS_PY_WORK}/profiles)
set_tests_properties(py_api_profiles PROPERTIES ENVIRONMENT "ROLLSIM_LIB=$<TARGET_FILE:rollsim_shared>")
