# Included by CTest (a directory's TEST_INCLUDE_FILES) for a unit-test executable when SYLVA_BATCH_UNIT_TESTS is
# on: one CTest test per GoogleTest suite ("Suite.*", running exactly that suite's cases), instead of one per
# case. Under the sanitizers a process costs about 0.2 s before its first test (ASan's start, OpenCV and GDAL
# loading), more than most unit tests take (docs/testing.md, "Where the time goes").
#
# Set before the include: SYLVA_SUITES_EXE (the executable), SYLVA_SUITES_FILTER (a gtest filter or empty),
# SYLVA_SUITES_LABELS, SYLVA_SUITES_LOCK (a resource lock or empty).
if(NOT EXISTS "${SYLVA_SUITES_EXE}")
  # Not built: a test that fails names the missing executable instead of vanishing from the run.
  add_test("${SYLVA_SUITES_EXE}_NOT_BUILT" "${SYLVA_SUITES_EXE}")
  return()
endif()
set(_args --gtest_list_tests)
if(SYLVA_SUITES_FILTER)
  list(APPEND _args "--gtest_filter=${SYLVA_SUITES_FILTER}")
endif()
execute_process(COMMAND "${SYLVA_SUITES_EXE}" ${_args} OUTPUT_VARIABLE _out ERROR_VARIABLE _err
  RESULT_VARIABLE _rc TIMEOUT 60)
if(NOT _rc EQUAL 0)
  add_test("${SYLVA_SUITES_EXE}_CANNOT_LIST_TESTS" "${SYLVA_SUITES_EXE}" --gtest_list_tests)
  return()
endif()
string(REPLACE "\n" ";" _lines "${_out}")
set(_suite "")
set(_cases "")
macro(_sylva_add_suite)
  if(_suite AND _cases)
    list(JOIN _cases ":" _filter)
    add_test("${_suite}.*" "${SYLVA_SUITES_EXE}" "--gtest_filter=${_filter}")
    set_tests_properties("${_suite}.*" PROPERTIES LABELS "${SYLVA_SUITES_LABELS}"
      ENVIRONMENT "SYLVA_TEST_LABEL=unit")
    if(SYLVA_SUITES_LOCK)
      set_tests_properties("${_suite}.*" PROPERTIES RESOURCE_LOCK "${SYLVA_SUITES_LOCK}")
    endif()
  endif()
endmacro()
foreach(_line IN LISTS _lines)
  if(_line MATCHES "^([^ ]+)\\.( |$)")
    # "Suite." or "Prefix/Suite/0.  # TypeParam = …": a new suite.
    _sylva_add_suite()
    set(_suite "${CMAKE_MATCH_1}")
    set(_cases "")
  elseif(_line MATCHES "^  ([^ ]+)")
    # "  Case" or "  Case/3  # GetParam() = …"
    list(APPEND _cases "${_suite}.${CMAKE_MATCH_1}")
  endif()
endforeach()
_sylva_add_suite()
