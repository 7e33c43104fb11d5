# CTest test of a study's MPI build (check/cases.hpp): run it on two ranks into its own folders, then
# compare every result file and figure with the serial run's (fem-compare-results).
#   cmake -DMPIEXEC=... -DPROGRAM=... -DSOURCE=... -DSERIAL=... -DSERIAL_FIGURES=... -DOUT=...
#         -DCOMPARE=... -P mpi_study_test.cmake
file(REMOVE_RECURSE ${OUT})
set(ENV{OMPI_ALLOW_RUN_AS_ROOT} 1)          # containers run tests as root
set(ENV{OMPI_ALLOW_RUN_AS_ROOT_CONFIRM} 1)
set(ENV{OMPI_MCA_rmaps_base_oversubscribe} 1)  # two ranks even on a one-core machine
execute_process(COMMAND ${MPIEXEC} -n 2 ${PROGRAM} --results ${OUT}/results --figures ${OUT}/figures
                WORKING_DIRECTORY ${SOURCE} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the study on two MPI ranks exited with ${rc}")
endif()
execute_process(COMMAND ${COMPARE} ${SERIAL} ${OUT}/results ${SERIAL_FIGURES} ${OUT}/figures RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the MPI run differs from the serial run")
endif()
