# prm-driven system tests. Each runs coshell on a scene from prm/ and checks
# the result against a reference stated here, on the test's command line.

set(COSHELL_RUN_AND_CHECK ${CMAKE_CURRENT_SOURCE_DIR}/scripts/run_and_check.py)
set(COSHELL_EXPECT_FAILURE ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_failure.py)
set(COSHELL_PRM ${CMAKE_SOURCE_DIR}/prm)
set(no_vtu "Output/Write VTU=false")

# coshell_scene_test(NAME PRM [LABELS l...] ARGS run_and_check arguments...)
function(coshell_scene_test name prm)
  cmake_parse_arguments(T "" "" "LABELS;ARGS" ${ARGN})
  add_test(NAME ${name}
           COMMAND ${COSHELL_PYTHON} ${COSHELL_RUN_AND_CHECK}
                   --coshell $<TARGET_FILE:coshell>
                   --prm ${COSHELL_PRM}/${prm}
                   --output ${CMAKE_CURRENT_BINARY_DIR}/output/${name}
                   ${T_ARGS})
  if(NOT T_LABELS)
    set(T_LABELS system)
  endif()
  set_tests_properties(${name} PROPERTIES LABELS "${T_LABELS}")
endfunction()

# coshell_bad_input_test(NAME PATTERN coshell arguments...)
function(coshell_bad_input_test name pattern)
  add_test(NAME bad_input.${name}
           COMMAND ${COSHELL_PYTHON} ${COSHELL_EXPECT_FAILURE}
                   --pattern ${pattern}
                   --output ${CMAKE_CURRENT_BINARY_DIR}/output/bad_input.${name}
                   -- $<TARGET_FILE:coshell> ${ARGN}
                   --output ${CMAKE_CURRENT_BINARY_DIR}/output/bad_input.${name})
  set_tests_properties(bad_input.${name} PROPERTIES LABELS "bad_input")
endfunction()

include(${CMAKE_CURRENT_SOURCE_DIR}/plate_tests.cmake)
include(${CMAKE_CURRENT_SOURCE_DIR}/bad_input_tests.cmake)
include(${CMAKE_CURRENT_SOURCE_DIR}/nonlinear_tests.cmake)
set(COSHELL_TESTED_MEMBRANES cst andes)
include(${CMAKE_CURRENT_SOURCE_DIR}/obstacle_course_tests.cmake)
include(${CMAKE_CURRENT_SOURCE_DIR}/dynamics_tests.cmake)
include(${CMAKE_CURRENT_SOURCE_DIR}/contact_tests.cmake)
include(${CMAKE_CURRENT_SOURCE_DIR}/iol_tests.cmake)
include(${CMAKE_CURRENT_SOURCE_DIR}/mpi_tests.cmake)
include(${CMAKE_CURRENT_SOURCE_DIR}/thickness_tests.cmake)

# Output/Format = hdf5: HDF5 files with duplicate vertices merged and the
# solution.xdmf index, read back with h5py: a static plate (its centre
# deflection in the file equals summary.json's within single precision)
# and a dynamic series (one grid per step at increasing times).
set(CHECK_HDF5 ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_hdf5_output.py)
add_test(NAME output.hdf5_xdmf.clamped_square
  COMMAND ${COSHELL_PYTHON} ${CHECK_HDF5} --coshell $<TARGET_FILE:coshell>
          --prm ${COSHELL_PRM}/plates/clamped_square_pressure.prm
          --output ${CMAKE_CURRENT_BINARY_DIR}/output/output.hdf5_xdmf.clamped_square
          --set "Mesh/Refinement levels=1" --qoi center_deflection 5 5 0)
add_test(NAME output.hdf5_xdmf.free_flying_plate_series
  COMMAND ${COSHELL_PYTHON} ${CHECK_HDF5} --coshell $<TARGET_FILE:coshell>
          --prm ${COSHELL_PRM}/dynamics/free_flying_plate.prm
          --output ${CMAKE_CURRENT_BINARY_DIR}/output/output.hdf5_xdmf.free_flying_plate
          --set "Time integration/End time=0.1" --set "Output/Write VTU=true")
set_tests_properties(output.hdf5_xdmf.clamped_square
  output.hdf5_xdmf.free_flying_plate_series PROPERTIES LABELS system)
