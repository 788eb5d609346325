# Distributed runs (issue: scale-out). Each scene runs serially and on two
# MPI ranks (METIS partition, Trilinos matrices on MPI_COMM_WORLD) and must
# give the serial answer to 1e-10 relative: every quantity of interest, the
# CSV histories and, in double precision, every vertex's displacement and
# rotation (Output/Vertex table). The reference is the serial code, an
# independent path through the same physics: different cell ownership, DoF
# numbering, matrix assembly and solver.
find_program(COSHELL_MPIRUN NAMES mpirun mpiexec)
if(NOT COSHELL_MPIRUN)
  message(STATUS "mpirun not found: the mpi.* tests are skipped")
  return()
endif()

set(CHECK_MPI ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_mpi_equals_serial.py)
set(mpi_environment "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1")

# coshell_mpi_test(NAME PRM METHOD [--set overrides...]); METHOD "default"
# sets no Linear solver/Method, so each run takes the default (auto).
function(coshell_mpi_test name prm method)
  set(method_setting --set "Linear solver/Method=${method}")
  if(method STREQUAL "default")
    set(method_setting)
  endif()
  add_test(NAME mpi.${name}
    COMMAND ${COSHELL_PYTHON} ${CHECK_MPI} --coshell $<TARGET_FILE:coshell>
            --mpirun ${COSHELL_MPIRUN} --ranks 2 --tolerance 1e-10
            --prm ${COSHELL_PRM}/${prm}
            --output ${CMAKE_CURRENT_BINARY_DIR}/output/mpi.${name}
            ${method_setting}
            --set "Output/Vertex table=true" ${ARGN})
  set_tests_properties(mpi.${name} PROPERTIES LABELS mpi
                       ENVIRONMENT "${mpi_environment}")
endfunction()

# Linear statics, refinement studies of 4 levels (64 .. 4096 triangles).
coshell_mpi_test(clamped_square_mumps plates/clamped_square_pressure.prm
                 amesos-mumps)
# The default method, auto: CHOLMOD serially, MUMPS on the two ranks.
coshell_mpi_test(clamped_square_default_solver
                 plates/clamped_square_pressure.prm default
                 --expect-solvers cholmod amesos-mumps)
coshell_mpi_test(scordelis_lo_mumps obstacle_course/scordelis_lo_roof.prm
                 amesos-mumps)
# Three ranks (uneven parts, oversubscribed on two cores) and HDF5/XDMF
# output, which rank 0 writes for the whole mesh.
coshell_mpi_test(scordelis_lo_3_ranks_hdf5 obstacle_course/scordelis_lo_roof.prm
                 amesos-mumps --ranks 3 --set "Output/Format=hdf5")
# AMG with the rigid-body near-null space, distributed over the two ranks;
# the tolerance is tight so that both runs converge to the same solution.
coshell_mpi_test(scordelis_lo_cg_amg obstacle_course/scordelis_lo_roof.prm
                 cg-amg --set "Linear solver/Tolerance=1e-13")
# Co-rotational statics: the end-moment cantilever (20 load steps, 104
# Newton iterations), with MUMPS and with GMRES + AMG on the non-symmetric
# consistent tangent.
coshell_mpi_test(cantilever_end_moment_mumps benchmarks/cantilever_end_moment.prm
                 amesos-mumps)
coshell_mpi_test(cantilever_end_moment_gmres_amg
                 benchmarks/cantilever_end_moment.prm gmres-amg
                 --set "Linear solver/Tolerance=1e-12")
# Dynamics: the clamped plate released after a static pressure stage, made
# co-rotational, generalized alpha for 50 steps.
coshell_mpi_test(cantilever_plate_dynamics_mumps
                 dynamics/cantilever_plate_free_vibration.prm amesos-mumps
                 --set "Element/Formulation=corotational"
                 --set "Stage 2/Duration=1.8" --set "Output/Write VTU=true"
                 --set "Output/Steps between outputs=0")
# Restart across rank counts: the two-rank run resumes from the middle
# checkpoint of the serial one (checkpoints store vectors by vertex).
# Its static preload takes the exact tangent (Geometric stiffness =
# current forces), for which the 1e-10 holds. The last acceleration is
# held to ten times its round-off floor, which the checker measures with a
# third run (a serial restart with UMFPACK): 1e-10 sits at that floor.
# The two ranks' acceleration and a serial UMFPACK or MUMPS restart's part
# from the serial run's by about 1e-10, all in the in-plane components,
# whose own size is 1e-4 of the largest (the measured values by machine
# are in doc/validation.md).
coshell_mpi_test(cantilever_plate_dynamics_restart
                 dynamics/cantilever_plate_free_vibration.prm amesos-mumps
                 --set "Element/Formulation=corotational"
                 --set "Nonlinear solver/Geometric stiffness=current forces"
                 --set "Stage 2/Duration=1.8" --set "Output/Write VTU=true"
                 --set "Output/Steps between outputs=0"
                 --set "Output/Checkpoint interval=0.5" --restart-from-middle)
# Contact: the shell is distributed, the rigid plane and the barrier terms
# are computed on every rank.
# The parallel run writes Output/Format = pvtu: one piece per rank.
coshell_mpi_test(plate_on_plane_mumps contact/plate_on_plane.prm amesos-mumps
                 --check-pvtu)
# Self contact on two ranks: pairs couple vertices of different ranks, so
# the distributed tangent's pattern grows by them, and each rank adds the
# rows it owns of the pair terms every rank computes. A plate resting on
# a clamped plate of the same mesh (11 Newton iterations), and the
# roll-up's static stage (40 load steps, 185 iterations), whose tip comes
# to rest on the tail as the pair list changes from step to step. The
# roll-up's dynamic stage is left out: through the snap it amplifies
# round-off (the two runs part by 1e-12 at first, and by about 50x per
# three steps) and comes to rest 2e-4 apart; so do two serial runs, one
# with UMFPACK and one with MUMPS (tip_ux -5.28334 against -5.28442).
coshell_mpi_test(self_contact_plate_on_plate_mumps contact/plate_on_plate.prm
                 amesos-mumps)
# The tip rotation is the y component of the wrapped rotation vector of a
# 6.11 rad turn, 0.17 rad: it is judged against the rotation field's
# largest entry, 3.13 rad, as every point value is against its field
# (1.1e-10 of itself, 5.8e-12 of the field, on the AMD EPYC machine).
# The roll-up's statics pins extrapolated forces throughout: with the
# default (auto) its one failed step (load factor 0.974) returns the rest
# of the stage to the exact tangent, whose last step converges linearly
# and stops at a relative residual of 6.8e-8 against the tolerance 1e-7;
# the tip rotation of 1 and 2 ranks then differs by 2.8e-10 (the values
# differ in the 10th digit either way; 219 corrections against 216). That
# is round-off of a residual at its floor, not a rank effect; the
# tolerance is not changed and the test keeps the path it was made for.
coshell_mpi_test(self_contact_rollup_statics_mumps
                 contact/self_contact_rollup.prm amesos-mumps
                 --set "Stage 2/Analysis type=none"
                 --set "Nonlinear solver/Geometric stiffness=extrapolated forces")
# The application on two ranks: the IOL injection's fold stage (coarse
# lens, 98 time steps, 731 Newton iterations): self contact, the
# cartridge's wings, rod and plunger with friction, all through the
# distributed tangent. Measured: vertex fields 2e-15, histories 2.4e-13,
# contact forces 1e-12, the same 731 iterations. The smallest gap of each
# step is a minimum over every Newton iterate, converged or not, and an
# unconverged iterate carries the linear solver's round-off times the
# barrier tangent's conditioning: two serial runs that differ only in the
# direct solver (UMFPACK or KLU against MUMPS) differ there by 3e-10 and
# 5e-10 of its largest value, as the two-rank run does (6.7e-10). That
# column alone is held to 1e-8. The test pins the consistent tangent, not
# the scene's symmetric part of it: with the symmetric part every
# converged quantity still agrees to 1e-12 or better, but the
# unconverged iterates are further from round-off's reach: the smallest
# gap differs by 1.5e-6 between 1 and 2 ranks, and by 9e-7 and 1e-7
# between serial runs with UMFPACK or KLU and with MUMPS. A solver
# effect, not a rank effect; the tolerance is not changed.
coshell_mpi_test(iol_fold_mumps iol/injection.prm amesos-mumps
                 --set "Mesh/Gmsh parameters=optic_mesh_size = 0.9, haptic_mesh_size = 0.35"
                 ${fold_stage_only}  # iol_tests.cmake's
                 --set "Nonlinear solver/Tangent=consistent"
                 --iterate-tolerance 1e-8)

# coshell_mpi_bad_input_test(NAME PATTERN RANKS [ONCE] coshell arguments...):
# the run under mpirun must stop with a message matching PATTERN; with ONCE
# (an error every rank meets alike) one line of stderr only must match it.
function(coshell_mpi_bad_input_test name pattern ranks)
  cmake_parse_arguments(PARSE_ARGV 3 arg "ONCE" "" "")
  set(once)
  if(arg_ONCE)
    set(once --once)
  endif()
  set(output ${CMAKE_CURRENT_BINARY_DIR}/output/bad_input.${name})
  add_test(NAME bad_input.${name}
    COMMAND ${COSHELL_PYTHON} ${COSHELL_EXPECT_FAILURE} --pattern ${pattern}
            --output ${output} ${once}
            -- ${COSHELL_MPIRUN} --oversubscribe -np ${ranks}
            $<TARGET_FILE:coshell> ${arg_UNPARSED_ARGUMENTS} --output ${output})
  set_tests_properties(bad_input.${name} PROPERTIES LABELS "bad_input;mpi"
                       ENVIRONMENT "${mpi_environment}")
endfunction()

# A solver that runs on one rank only (asked for by name; the default,
# auto, takes MUMPS) stops with a message naming the parameter and the
# methods that do run distributed; so do what runs on one rank only, and a
# mesh too small for the ranks. Every rank meets these alike, and the
# message is printed once.
coshell_mpi_bad_input_test(mpi_serial_solver
  "Linear solver/Method = cholmod runs on one rank.*amesos-mumps" 2 ONCE
  ${COSHELL_PRM}/plates/clamped_square_pressure.prm
  --set "Linear solver/Method=cholmod")
coshell_mpi_bad_input_test(mpi_modes "Analysis/Type = modes runs on one rank" 2
  ONCE ${COSHELL_PRM}/dynamics/cantilever_plate_modes.prm
  --set "Linear solver/Method=amesos-mumps")
coshell_mpi_bad_input_test(mpi_interactive "--interactive runs on one rank" 2
  ONCE ${COSHELL_PRM}/dynamics/free_flying_plate.prm --interactive
  --set "Linear solver/Method=amesos-mumps")
coshell_mpi_bad_input_test(mpi_mesh_too_small
  "the mesh has 4 triangles, too few for 3 MPI ranks" 3 ONCE
  ${COSHELL_PRM}/plates/clamped_square_pressure.prm
  --set "Mesh/Subdivisions x=1" --set "Mesh/Subdivisions y=1"
  --set "Mesh/Refinement levels=0" --set "Linear solver/Method=amesos-mumps")
# The same refusal when the rows are distributed: every rank stops, the one
# holding the DoF names it.
coshell_mpi_bad_input_test(mpi_load_on_unstiffened_dof
  "a load acts on DoF [0-9]+, which no element stiffens" 2 ONCE
  ${COSHELL_PRM}/plates/clamped_square_pressure.prm
  --set "Element/Membrane element=off"
  --set "Loads/Point forces=0.5 0.5 0 : 1 0 0" --set "Mesh/Refinement levels=1"
  --set "Linear solver/Method=amesos-mumps")
