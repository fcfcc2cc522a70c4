# Helpers that make a new test a one-liner.
#
#   sb_add_gtest(NAME [PROGRAM P] SOURCES a.cpp b.cpp LIBS lib1 lib2 [LABELS l] [SHARDS n])
#       the ctest test NAME: the GoogleTest tests of SOURCES. Without PROGRAM, a GoogleTest
#       executable NAME of its own. With PROGRAM P, the sources join the executable P, which
#       the other tests naming P share (one per tests/ folder: its files compile together as
#       a unity build and it links once), and the test runs P with a --gtest_filter of the
#       suites its SOURCES define (read from the TEST/TEST_F/TEST_P lines; a suite may belong
#       to one test of a program only, checked here). With SHARDS n, the ctest tests
#       NAME_1ofn ... NAME_nofn each run every n-th GoogleTest test of it (GoogleTest's own
#       sharding, GTEST_TOTAL_SHARDS and GTEST_SHARD_INDEX, of the tests the filter selects), so
#       a long program's tests run on both cores; they are scheduled first (COST).
#   sb_add_mpi_gtest(NAME [PROGRAM P] NPROCS n [n2 ...] SOURCES ... LIBS ... [LABELS l])
#       the same, launched as `mpiexec -n n` with the flags a root CI machine needs;
#       the tests get MPI initialised by tests/support/mpi_gtest_main.cpp. With several
#       rank counts, one program runs as the ctest tests NAME<n>, NAME<n2>, ...
#   sb_add_benchmark(NAME SOURCES ... LIBS ...)
#       a Google Benchmark program (not run by ctest), built by the target `benchmarks`.
#   sb_benchmark_target(TARGET)
#       a measuring program (a benchmark, a driver for callgrind or a study run by hand): left
#       out of the target `all`, which CI builds (build preset release-tests), and built by the
#       target `benchmarks`, which the build presets release and debug build with `all`.
#   sb_mpi_environment(TEST...)
#       Open MPI's environment (scripts/openmpi.env) for tests that start MPI programs without
#       the shell tests' prologue (tests/support/prologue.sh), e.g. Python tests.

set(SKEWBRIDGE_TEST_DATA_DIR "${PROJECT_SOURCE_DIR}/tests/data")
set(SKEWBRIDGE_SHARED_DIR "${PROJECT_SOURCE_DIR}/../shared")
# The NAME=VALUE lines of scripts/openmpi.env, as a list for the ENVIRONMENT test property.
file(STRINGS "${PROJECT_SOURCE_DIR}/scripts/openmpi.env" SKEWBRIDGE_MPI_ENVIRONMENT
     REGEX "^[A-Za-z_][A-Za-z0-9_]*=")
set_property(DIRECTORY "${PROJECT_SOURCE_DIR}" APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
             "${PROJECT_SOURCE_DIR}/scripts/openmpi.env")

# The GoogleTest programs' own code (set-up, oracles, brute-force checks) is compiled with -Og
# in every preset but Debug: the Eigen expressions of the test files made about half of each
# preset's compile time at -O3 (release) or -O1 (sanitizers), while a test's run time is mostly
# that of the libraries under test, which keep the preset's flags (an inline function of a
# library header that a test file instantiates may run at -Og in that program). x86-64 without
# -march has no fused multiply-add, so a test's own arithmetic gives the same bits at any -O.
# The benchmarks and the measuring drivers keep the preset's flags.
set(SKEWBRIDGE_TEST_CODE_OPTIONS "$<$<NOT:$<CONFIG:Debug>>:-Og>")

# sb_unity_build(TARGET SOURCE...): a test program of several files is compiled as one
# translation unit per 8 files (CMake's unity build): the Eigen and library templates its files
# share are instantiated and compiled once, not once per file. Each file's anonymous namespace
# then shares a scope with the other files': a file whose names collide puts its anonymous
# namespace in a namespace named after the file (tests/dynamics/gap_root_test.cpp).
function(sb_unity_build name)
  list(LENGTH ARGN count)
  if(count GREATER 1)
    set_target_properties(${name} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
  endif()
endfunction()

function(sb_mpi_environment)
  set_tests_properties(${ARGN} PROPERTIES ENVIRONMENT "${SKEWBRIDGE_MPI_ENVIRONMENT}")
endfunction()

# Test programs shared by several ctest tests (PROGRAM P): P is created by the first test that
# names it, its tests are registered at the end of that folder (sb_add_shared_gtests), when
# every test's sources are known. Each test's --gtest_filter selects its sources' suites
# (`S.*:*/S.*`, the second for a value-parameterised suite S run as PREFIX/S); a suite whose
# tests are spread over the sources of several tests of P is selected by its test names
# instead. The suites and names are read from each source's TEST, TEST_F and TEST_P lines; a
# change of a source reconfigures, so the filters follow it.

# sb_gtest_cases(OUT SOURCE): in OUT, the GoogleTest tests that SOURCE defines, as S.NAME (TEST,
# TEST_F) or S.NAME/P (TEST_P).
function(sb_gtest_cases out source)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${source}")
  file(READ "${source}" text)
  set(name "[A-Za-z0-9_]+")
  set(space "[ \t\r\n]*")
  string(REGEX MATCHALL "\n[ \t]*TEST(_F|_P)?${space}\\(${space}${name}${space},${space}${name}"
         found "\n${text}")
  set(cases "")
  foreach(match IN LISTS found)
    string(REGEX REPLACE "[ \t\r\n]" "" match "${match}")
    string(REGEX MATCH "^TEST(_F|_P)?\\((${name}),(${name})$" ok "${match}")
    if(CMAKE_MATCH_1 STREQUAL "_P")
      list(APPEND cases "${CMAKE_MATCH_2}.${CMAKE_MATCH_3}/P")
    else()
      list(APPEND cases "${CMAKE_MATCH_2}.${CMAKE_MATCH_3}")
    endif()
  endforeach()
  if(NOT cases)
    message(FATAL_ERROR "${source}: no TEST, TEST_F or TEST_P to select its tests by")
  endif()
  set(${out} "${cases}" PARENT_SCOPE)
endfunction()

# sb_gtest_program(PROGRAM MAIN_LIBS...): creates the test executable PROGRAM once (with the
# test code's flags and data folders), linked to MAIN_LIBS (the GoogleTest main, or MPI's).
function(sb_gtest_program program)
  if(TARGET ${program})
    return()
  endif()
  add_executable(${program})
  target_link_libraries(${program} PRIVATE ${ARGN})
  target_compile_options(${program} PRIVATE ${SKEWBRIDGE_TEST_CODE_OPTIONS})
  target_compile_definitions(${program} PRIVATE
    SKEWBRIDGE_TEST_DATA_DIR="${SKEWBRIDGE_TEST_DATA_DIR}"
    SKEWBRIDGE_SHARED_DIR="${SKEWBRIDGE_SHARED_DIR}")
endfunction()

# sb_add_test_of(TEST PROGRAM KIND FILTER SHARDS NPROCS LABELS): the ctest test(s) of one
# sb_add_gtest (KIND gtest) or sb_add_mpi_gtest (KIND mpi) running PROGRAM with FILTER (an
# argument, or empty).
function(sb_add_test_of name program kind filter shards nprocs labels)
  if(kind STREQUAL "mpi")
    list(LENGTH nprocs counts)
    foreach(n IN LISTS nprocs)
      set(test ${name})
      if(counts GREATER 1)
        set(test ${name}${n})
      endif()
      add_test(NAME ${test}
        COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} ${n} --oversubscribe
                ${MPIEXEC_PREFLAGS} $<TARGET_FILE:${program}> ${MPIEXEC_POSTFLAGS} ${filter})
      set_tests_properties(${test} PROPERTIES LABELS "mpi;${labels}" PROCESSORS ${n})
      sb_mpi_environment(${test})
    endforeach()
    return()
  endif()
  if(NOT shards OR shards LESS 2)
    add_test(NAME ${name} COMMAND ${program} ${filter})
    set_tests_properties(${name} PROPERTIES LABELS "unit;${labels}")
    return()
  endif()
  math(EXPR last "${shards} - 1")
  foreach(i RANGE ${last})
    math(EXPR k "${i} + 1")
    set(test ${name}_${k}of${shards})
    add_test(NAME ${test} COMMAND ${program} ${filter})
    set_tests_properties(${test} PROPERTIES LABELS "unit;${labels}" COST 1000
      ENVIRONMENT "GTEST_TOTAL_SHARDS=${shards};GTEST_SHARD_INDEX=${i}")
  endforeach()
endfunction()

# sb_join_program(NAME PROGRAM KIND SHARDS NPROCS LABELS SOURCES...): the test NAME's part of
# the shared PROGRAM: its sources join it, its ctest tests wait for the end of the folder.
function(sb_join_program name program kind shards nprocs labels)
  get_property(home GLOBAL PROPERTY SB_PROGRAM_HOME_${program})
  if(NOT home)
    set_property(GLOBAL PROPERTY SB_PROGRAM_HOME_${program} "${CMAKE_CURRENT_SOURCE_DIR}")
    # (Through EVAL: a deferred call expands its arguments when it runs, in the folder's scope.)
    cmake_language(EVAL CODE "cmake_language(DEFER CALL sb_add_shared_gtests [[${program}]])")
  elseif(NOT home STREQUAL CMAKE_CURRENT_SOURCE_DIR)
    message(FATAL_ERROR "${name}: the test program ${program} belongs to ${home}")
  endif()
  set_target_properties(${program} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
  set(cases "")
  foreach(source IN LISTS ARGN)
    get_filename_component(path "${source}" ABSOLUTE)
    sb_gtest_cases(found "${path}")
    list(APPEND cases ${found})
  endforeach()
  string(REPLACE ";" "," cases "${cases}")
  set_property(GLOBAL APPEND PROPERTY SB_PROGRAM_TESTS_${program} ${name})
  set_property(GLOBAL PROPERTY SB_TEST_${name}
    "${kind}|${shards}|${nprocs}|${labels}|${cases}")
endfunction()

# sb_add_shared_gtests(PROGRAM): the ctest tests of the shared PROGRAM, each with its filter.
function(sb_add_shared_gtests program)
  get_property(tests GLOBAL PROPERTY SB_PROGRAM_TESTS_${program})
  set(filters "")
  # The tests of each suite.
  foreach(test IN LISTS tests)
    get_property(spec GLOBAL PROPERTY SB_TEST_${test})
    string(REPLACE "|" ";" spec "${spec}")
    list(GET spec 4 cases)
    string(REPLACE "," ";" cases "${cases}")
    foreach(case IN LISTS cases)
      string(REGEX REPLACE "[.].*" "" suite "${case}")
      set_property(GLOBAL APPEND PROPERTY SB_SUITE_${program}_${suite} ${test})
    endforeach()
  endforeach()
  foreach(test IN LISTS tests)
    get_property(spec GLOBAL PROPERTY SB_TEST_${test})
    string(REPLACE "|" ";" spec "${spec}")
    list(GET spec 0 kind)
    list(GET spec 1 shards)
    list(GET spec 2 nprocs)
    list(GET spec 3 labels)
    list(GET spec 4 cases)
    string(REPLACE "," ";" nprocs "${nprocs}")
    string(REPLACE "," ";" labels "${labels}")
    string(REPLACE "," ";" cases "${cases}")
    set(patterns "")
    foreach(case IN LISTS cases)
      string(REGEX REPLACE "[.].*" "" suite "${case}")
      get_property(owners GLOBAL PROPERTY SB_SUITE_${program}_${suite})
      list(REMOVE_DUPLICATES owners)
      list(LENGTH owners count)
      if(count EQUAL 1)
        list(APPEND patterns "${suite}.*" "*/${suite}.*")
      elseif(case MATCHES "/P$")
        string(REGEX REPLACE "/P$" "/*" case "${case}")
        list(APPEND patterns "*/${case}")
      else()
        list(APPEND patterns "${case}")
      endif()
    endforeach()
    list(REMOVE_DUPLICATES patterns)
    string(REPLACE ";" ":" filter "${patterns}")
    sb_add_test_of(${test} ${program} ${kind} "--gtest_filter=${filter}" "${shards}"
                   "${nprocs}" "${labels}")
    string(APPEND filters "${test}\t${filter}\n")
  endforeach()
  # The filters are read from the sources' text: a test case they miss (a macro of another
  # name, a suite defined through a helper) would build and never run. This test lists the
  # program's cases and requires each to be selected by exactly one of its tests' filters.
  set(list_file "${CMAKE_CURRENT_BINARY_DIR}/${program}.filters")
  file(GENERATE OUTPUT "${list_file}" CONTENT "$<TARGET_FILE:${program}>\n${filters}")
  add_test(NAME lint_gtest_filters_${program}
    COMMAND bash ${PROJECT_SOURCE_DIR}/tests/lint/check_gtest_filters.sh "${list_file}")
  set_tests_properties(lint_gtest_filters_${program} PROPERTIES LABELS "lint")
  sb_mpi_environment(lint_gtest_filters_${program})
endfunction()

function(sb_add_gtest name)
  cmake_parse_arguments(ARG "" "SHARDS;PROGRAM" "SOURCES;LIBS;LABELS" ${ARGN})
  if(NOT SKEWBRIDGE_BUILD_TESTS)
    return()
  endif()
  find_package(GTest REQUIRED)
  set(program ${name})
  if(ARG_PROGRAM)
    set(program ${ARG_PROGRAM})
  endif()
  sb_gtest_program(${program} GTest::gtest GTest::gtest_main GTest::gmock)
  target_sources(${program} PRIVATE ${ARG_SOURCES})
  target_link_libraries(${program} PRIVATE ${ARG_LIBS})
  if(ARG_PROGRAM)
    string(REPLACE ";" "," labels "${ARG_LABELS}")
    sb_join_program(${name} ${program} gtest "${ARG_SHARDS}" "" "${labels}" ${ARG_SOURCES})
  else()
    sb_unity_build(${program} ${ARG_SOURCES})
    sb_add_test_of(${name} ${program} gtest "" "${ARG_SHARDS}" "" "${ARG_LABELS}")
  endif()
endfunction()

function(sb_add_mpi_gtest name)
  cmake_parse_arguments(ARG "" "PROGRAM" "NPROCS;SOURCES;LIBS;LABELS" ${ARGN})
  if(NOT SKEWBRIDGE_BUILD_TESTS OR NOT SKEWBRIDGE_WITH_MPI)
    return()
  endif()
  if(NOT ARG_NPROCS)
    set(ARG_NPROCS 2)
  endif()
  find_package(GTest REQUIRED)
  # The main of every MPI test program, compiled once.
  if(NOT TARGET sb_mpi_gtest_main)
    add_library(sb_mpi_gtest_main OBJECT "${PROJECT_SOURCE_DIR}/tests/support/mpi_gtest_main.cpp")
    target_link_libraries(sb_mpi_gtest_main PUBLIC MPI::MPI_C GTest::gtest GTest::gmock)
    # MPI's C API only, as in the jobs library (Open MPI's C++ bindings are not linked).
    target_compile_definitions(sb_mpi_gtest_main PRIVATE OMPI_SKIP_MPICXX=1 MPICH_SKIP_MPICXX=1)
  endif()
  set(program ${name})
  if(ARG_PROGRAM)
    set(program ${ARG_PROGRAM})
  endif()
  sb_gtest_program(${program} sb_mpi_gtest_main)
  target_sources(${program} PRIVATE ${ARG_SOURCES})
  target_link_libraries(${program} PRIVATE ${ARG_LIBS})
  if(ARG_PROGRAM)
    string(REPLACE ";" "," labels "${ARG_LABELS}")
    string(REPLACE ";" "," nprocs "${ARG_NPROCS}")
    sb_join_program(${name} ${program} mpi "" "${nprocs}" "${labels}" ${ARG_SOURCES})
  else()
    sb_unity_build(${program} ${ARG_SOURCES})
    sb_add_test_of(${name} ${program} mpi "" "" "${ARG_NPROCS}" "${ARG_LABELS}")
  endif()
endfunction()

# The measuring programs, built on demand or by the build presets release and debug.
add_custom_target(benchmarks)

function(sb_benchmark_target name)
  set_target_properties(${name} PROPERTIES EXCLUDE_FROM_ALL ON)
  add_dependencies(benchmarks ${name})
endfunction()

function(sb_add_benchmark name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  if(NOT SKEWBRIDGE_BUILD_BENCHMARKS)
    return()
  endif()
  find_package(benchmark REQUIRED)
  add_executable(${name} ${ARG_SOURCES})
  sb_benchmark_target(${name})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} benchmark::benchmark benchmark::benchmark_main)
  target_compile_definitions(${name} PRIVATE
    SKEWBRIDGE_TEST_DATA_DIR="${SKEWBRIDGE_TEST_DATA_DIR}")
endfunction()
