# Helpers that make a new test a one-liner.
#
#   sb_add_gtest(NAME SOURCES a.cpp b.cpp LIBS lib1 lib2 [LABELS l] [SHARDS n])
#       a GoogleTest executable run by ctest (one ctest entry per executable). With SHARDS n,
#       the ctest tests NAME_1ofn ... NAME_nofn each run every n-th GoogleTest test of it
#       (GoogleTest's own sharding, GTEST_TOTAL_SHARDS and GTEST_SHARD_INDEX), so a long
#       program's tests run on both cores; they are scheduled first (COST).
#   sb_add_mpi_gtest(NAME NPROCS n [n2 ...] SOURCES ... LIBS ... [LABELS l])
#       the same, launched as `mpiexec -n n` with the flags a root CI machine needs;
#       the tests get MPI initialised by tests/support/mpi_gtest_main.cpp. With several
#       rank counts, one executable NAME runs as the ctest tests NAME<n>, NAME<n2>, ...
#   sb_add_benchmark(NAME SOURCES ... LIBS ...)
#       a Google Benchmark program (built, not run by ctest).
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

function(sb_add_gtest name)
  cmake_parse_arguments(ARG "" "SHARDS" "SOURCES;LIBS;LABELS" ${ARGN})
  if(NOT SKEWBRIDGE_BUILD_TESTS)
    return()
  endif()
  find_package(GTest REQUIRED)
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} GTest::gtest GTest::gtest_main GTest::gmock)
  target_compile_options(${name} PRIVATE ${SKEWBRIDGE_TEST_CODE_OPTIONS})
  sb_unity_build(${name} ${ARG_SOURCES})
  target_compile_definitions(${name} PRIVATE
    SKEWBRIDGE_TEST_DATA_DIR="${SKEWBRIDGE_TEST_DATA_DIR}"
    SKEWBRIDGE_SHARED_DIR="${SKEWBRIDGE_SHARED_DIR}")
  if(NOT ARG_SHARDS OR ARG_SHARDS LESS 2)
    add_test(NAME ${name} COMMAND ${name})
    set_tests_properties(${name} PROPERTIES LABELS "unit;${ARG_LABELS}")
    return()
  endif()
  math(EXPR last "${ARG_SHARDS} - 1")
  foreach(i RANGE ${last})
    math(EXPR k "${i} + 1")
    set(test ${name}_${k}of${ARG_SHARDS})
    add_test(NAME ${test} COMMAND ${name})
    set_tests_properties(${test} PROPERTIES LABELS "unit;${ARG_LABELS}" COST 1000
      ENVIRONMENT "GTEST_TOTAL_SHARDS=${ARG_SHARDS};GTEST_SHARD_INDEX=${i}")
  endforeach()
endfunction()

function(sb_add_mpi_gtest name)
  cmake_parse_arguments(ARG "" "" "NPROCS;SOURCES;LIBS;LABELS" ${ARGN})
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
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} sb_mpi_gtest_main)
  target_compile_options(${name} PRIVATE ${SKEWBRIDGE_TEST_CODE_OPTIONS})
  sb_unity_build(${name} ${ARG_SOURCES})
  target_compile_definitions(${name} PRIVATE
    SKEWBRIDGE_TEST_DATA_DIR="${SKEWBRIDGE_TEST_DATA_DIR}"
    SKEWBRIDGE_SHARED_DIR="${SKEWBRIDGE_SHARED_DIR}")
  list(LENGTH ARG_NPROCS counts)
  foreach(n IN LISTS ARG_NPROCS)
    set(test ${name})
    if(counts GREATER 1)
      set(test ${name}${n})
    endif()
    add_test(NAME ${test}
      COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} ${n} --oversubscribe
              ${MPIEXEC_PREFLAGS} $<TARGET_FILE:${name}> ${MPIEXEC_POSTFLAGS})
    set_tests_properties(${test} PROPERTIES LABELS "mpi;${ARG_LABELS}" PROCESSORS ${n})
    sb_mpi_environment(${test})
  endforeach()
endfunction()

function(sb_add_benchmark name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  if(NOT SKEWBRIDGE_BUILD_BENCHMARKS)
    return()
  endif()
  find_package(benchmark REQUIRED)
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} benchmark::benchmark benchmark::benchmark_main)
  target_compile_definitions(${name} PRIVATE
    SKEWBRIDGE_TEST_DATA_DIR="${SKEWBRIDGE_TEST_DATA_DIR}")
endfunction()
