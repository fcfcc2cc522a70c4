# Helpers that make a new test a one-liner.
#
#   sb_add_gtest(NAME SOURCES a.cpp b.cpp LIBS lib1 lib2 [LABELS l])
#       a GoogleTest executable run by ctest (one ctest entry per executable).
#   sb_add_mpi_gtest(NAME NPROCS n SOURCES ... LIBS ... [LABELS l])
#       the same, launched as `mpiexec -n n` with the flags a root CI machine needs;
#       the tests get MPI initialised by tests/support/mpi_gtest_main.cpp.
#   sb_add_benchmark(NAME SOURCES ... LIBS ...)
#       a Google Benchmark program (built, not run by ctest).

set(SKEWBRIDGE_TEST_DATA_DIR "${PROJECT_SOURCE_DIR}/tests/data")
set(SKEWBRIDGE_SHARED_DIR "${PROJECT_SOURCE_DIR}/../shared")

function(sb_add_gtest name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS;LABELS" ${ARGN})
  if(NOT SKEWBRIDGE_BUILD_TESTS)
    return()
  endif()
  find_package(GTest REQUIRED)
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} GTest::gtest GTest::gtest_main GTest::gmock)
  target_compile_definitions(${name} PRIVATE
    SKEWBRIDGE_TEST_DATA_DIR="${SKEWBRIDGE_TEST_DATA_DIR}"
    SKEWBRIDGE_SHARED_DIR="${SKEWBRIDGE_SHARED_DIR}")
  add_test(NAME ${name} COMMAND ${name})
  set_tests_properties(${name} PROPERTIES LABELS "unit;${ARG_LABELS}")
endfunction()

function(sb_add_mpi_gtest name)
  cmake_parse_arguments(ARG "" "NPROCS" "SOURCES;LIBS;LABELS" ${ARGN})
  if(NOT SKEWBRIDGE_BUILD_TESTS OR NOT SKEWBRIDGE_WITH_MPI)
    return()
  endif()
  if(NOT ARG_NPROCS)
    set(ARG_NPROCS 2)
  endif()
  find_package(GTest REQUIRED)
  add_executable(${name} ${ARG_SOURCES} "${PROJECT_SOURCE_DIR}/tests/support/mpi_gtest_main.cpp")
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} MPI::MPI_C GTest::gtest GTest::gmock)
  target_compile_definitions(${name} PRIVATE
    SKEWBRIDGE_TEST_DATA_DIR="${SKEWBRIDGE_TEST_DATA_DIR}"
    SKEWBRIDGE_SHARED_DIR="${SKEWBRIDGE_SHARED_DIR}")
  add_test(NAME ${name}
    COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} ${ARG_NPROCS} --oversubscribe
            ${MPIEXEC_PREFLAGS} $<TARGET_FILE:${name}> ${MPIEXEC_POSTFLAGS})
  set_tests_properties(${name} PROPERTIES
    LABELS "mpi;${ARG_LABELS}"
    PROCESSORS ${ARG_NPROCS}
    ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")
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
