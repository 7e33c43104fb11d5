# CTest test of fem-sweep's MPI build (lib/explicit_case/sweep.hpp, check/cases.hpp): the sweep run
# serially and on two ranks into their own folders must give the same files apart from timings
# (fem-compare-results: JSON and tables without their timing keys and columns; the text summaries,
# which quote timings, only present in both).
#   cmake -DMPIEXEC=... -DSERIAL_PROGRAM=... -DMPI_PROGRAM=... -DSWEEP=... -DOUT=... -DCOMPARE=... -P mpi_sweep_test.cmake
file(REMOVE_RECURSE ${OUT})
set(ENV{OMPI_ALLOW_RUN_AS_ROOT} 1)          # containers run tests as root
set(ENV{OMPI_ALLOW_RUN_AS_ROOT_CONFIRM} 1)
set(ENV{OMPI_MCA_rmaps_base_oversubscribe} 1)  # two ranks even on a one-core machine
execute_process(COMMAND ${SERIAL_PROGRAM} ${SWEEP} --output ${OUT}/serial --jobs 1 --quiet RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the serial sweep exited with ${rc}")
endif()
execute_process(COMMAND ${MPIEXEC} -n 2 ${MPI_PROGRAM} ${SWEEP} --output ${OUT}/mpi --jobs 1 --quiet RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the sweep on two MPI ranks exited with ${rc}")
endif()
execute_process(COMMAND ${COMPARE} --skip summary.txt ${OUT}/serial ${OUT}/mpi RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the sweep on two MPI ranks differs from the serial sweep")
endif()
