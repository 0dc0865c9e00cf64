# Registers the tests of prism_tests with ctest in groups: one ctest test runs a few GoogleTest
# tests in one process (tests/README.md, "How ctest runs them"). Run by CMake in script mode
# after every link of prism_tests:
#
#   cmake -D TEST_EXECUTABLE=... -D CTEST_FILE=... -D THREADED_FILTER=a.*:b.c -P this file
#
# Why groups: starting prism_tests costs 0.45-0.8 s on the machines measured (the dynamic loader
# binds the ~270 shared libraries Debian's OpenImageIO pulls in; more under the sanitizers), paid
# once per ctest test. One process per GoogleTest test paid it ~700 times; one process per suite
# left the largest suites alone on one core at the end of the run. Groups of a few tests of one
# suite keep both cores busy and pay the start-up a few times per suite.
#
# Each test is in exactly one group, of one of three kinds with the labels scripts/test selects:
#   <Suite>.<n>           the default suite                    (no label)
#   <Suite>.threaded.<n>  tests matching THREADED_FILTER       (label `threaded`, TSan runs them)
#   <Suite>.long.<n>      tests named Long*, one per group     (label `long`, PRISM_LONG_TESTS=1)
# <Suite> is GoogleTest's suite with its instantiation prefix (Backends/AccelAccelerator).

foreach(required TEST_EXECUTABLE CTEST_FILE)
  if(NOT DEFINED ${required})
    message(FATAL_ERROR "register_test_groups.cmake: ${required} is not set")
  endif()
endforeach()

# Tests per process: enough to pay the start-up rarely, few enough that the slowest group (the
# app tests under a sanitizer, each starting prism several times) stays a small part of the run.
set(default_group_size 8)
set(threaded_group_size 4)

execute_process(COMMAND "${TEST_EXECUTABLE}" --gtest_list_tests
                OUTPUT_VARIABLE listing RESULT_VARIABLE listing_status TIMEOUT 60)
if(NOT listing_status EQUAL 0)
  message(FATAL_ERROR "register_test_groups.cmake: ${TEST_EXECUTABLE} --gtest_list_tests failed "
                      "(${listing_status})")
endif()

# GoogleTest filter patterns (* and ? wildcards) as anchored regular expressions.
set(threaded_regexes)
if(THREADED_FILTER)
  string(REPLACE ":" ";" threaded_patterns "${THREADED_FILTER}")
  foreach(pattern IN LISTS threaded_patterns)
    string(REGEX REPLACE "([][.+^$()|{}\\\\])" "\\\\\\1" regex "${pattern}")
    string(REPLACE "*" ".*" regex "${regex}")
    string(REPLACE "?" "." regex "${regex}")
    list(APPEND threaded_regexes "^${regex}$")
  endforeach()
endif()

# Walks the listing: "Suite." lines open a suite, indented lines are its tests (parameterised
# ones followed by "  # GetParam() = ...").
string(REPLACE "\n" ";" lines "${listing}")
set(suite "")
set(suites)
foreach(line IN LISTS lines)
  if(line MATCHES "^([A-Za-z0-9_/]+)\\.$")
    set(suite "${CMAKE_MATCH_1}")
    list(APPEND suites "${suite}")
    set(tests_${suite}_default)
    set(tests_${suite}_threaded)
    set(tests_${suite}_long)
  elseif(line MATCHES "^  ([A-Za-z0-9_/]+)" AND suite)
    set(name "${CMAKE_MATCH_1}")
    set(full "${suite}.${name}")
    if(name MATCHES "^Long")
      list(APPEND tests_${suite}_long "${full}")
    else()
      set(kind default)
      foreach(regex IN LISTS threaded_regexes)
        if(full MATCHES "${regex}")
          set(kind threaded)
          break()
        endif()
      endforeach()
      list(APPEND tests_${suite}_${kind} "${full}")
    endif()
  endif()
endforeach()

set(script "# Written by tests/cmake/register_test_groups.cmake from `${TEST_EXECUTABLE} --gtest_list_tests`.\n")
set(group_count 0)
set(test_count 0)
# Appends to `script` the groups of one kind of one suite.
function(add_groups suite kind size)
  set(tests ${tests_${suite}_${kind}})
  list(LENGTH tests count)
  if(count EQUAL 0)
    return()
  endif()
  if(kind STREQUAL "default")
    set(prefix "${suite}")
    set(properties "TIMEOUT 1800")
  elseif(kind STREQUAL "threaded")
    set(prefix "${suite}.threaded")
    set(properties "TIMEOUT 1800 LABELS threaded")
  else()
    set(prefix "${suite}.long")
    set(properties "TIMEOUT 3600 LABELS long ENVIRONMENT PRISM_LONG_TESTS=1")
  endif()
  set(index 1)
  set(start 0)
  while(start LESS count)
    math(EXPR remaining "${count} - ${start}")
    if(remaining GREATER size)
      set(remaining ${size})
    endif()
    list(SUBLIST tests ${start} ${remaining} group)
    list(JOIN group ":" filter)
    string(APPEND script
           "add_test([==[${prefix}.${index}]==] [==[${TEST_EXECUTABLE}]==] "
           "[==[--gtest_filter=${filter}]==])\n"
           "set_tests_properties([==[${prefix}.${index}]==] PROPERTIES ${properties})\n")
    math(EXPR start "${start} + ${remaining}")
    math(EXPR index "${index} + 1")
    math(EXPR group_count "${group_count} + 1")
  endwhile()
  math(EXPR test_count "${test_count} + ${count}")
  set(script "${script}" PARENT_SCOPE)
  set(group_count ${group_count} PARENT_SCOPE)
  set(test_count ${test_count} PARENT_SCOPE)
endfunction()

foreach(suite IN LISTS suites)
  add_groups("${suite}" default ${default_group_size})
  add_groups("${suite}" threaded ${threaded_group_size})
  add_groups("${suite}" long 1)
endforeach()
if(test_count EQUAL 0)
  message(FATAL_ERROR "register_test_groups.cmake: no tests in the listing of ${TEST_EXECUTABLE}")
endif()
string(APPEND script "# ${test_count} GoogleTest tests in ${group_count} ctest tests.\n")
file(WRITE "${CTEST_FILE}" "${script}")
