# Packaging (issue 41): `cmake --install` of this build into a virtual environment with Debian's
# Python packages and into a plain prefix, then the installed program, man page, header and
# library, the BLAS they load (RS_BLAS's, nothing else), and `import rollsim` solving Carter's
# case without ROLLSIM_LIB (.ci/install-check; CI also runs it from a fresh clone).
# Not in sanitizer builds: Python cannot load an instrumented librollsim.so.
if(CMAKE_C_FLAGS MATCHES "sanitize")
  return()
endif()
add_test(NAME install_route
  COMMAND bash ${PROJECT_SOURCE_DIR}/.ci/install-check --build-dir ${PROJECT_BINARY_DIR} ${RS_BLAS})
set_tests_properties(install_route PROPERTIES LABELS install TIMEOUT 300)
