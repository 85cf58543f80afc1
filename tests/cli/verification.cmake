# The verification suite at its reduced sizes (BENCHMARKS.md B1–B8; verification/README.md): each case
# script runs the program built here on its reduced cases, checks the criteria that apply at that size
# (and the program against its independent numpy references) and exits 1 on a failure without a
# measured reason. Label `verification`: `ctest -L verification`. The full sizes: verification/run.py.
# Runs are cached per binary (md5) in the build tree, so a rerun of an unchanged binary is quick.
set(PM_VERIFY_CACHE ${CMAKE_CURRENT_BINARY_DIR}/verification-cache)
set(PM_VERIFY_RESULTS ${CMAKE_CURRENT_BINARY_DIR}/verification)
foreach(pm_case b1_ghost_forces b2_plate_uniform b3_cracked_plate b4_cube_uniform b5_cracked_block
                b6_fracture_convergence b7_adaptive_fracture b8_damage_handover)
  add_test(NAME verification_${pm_case}
    COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/verification/${pm_case}.py --reduced --jobs 1
            --perimorph $<TARGET_FILE:perimorph_cli> --results ${PM_VERIFY_RESULTS} --cache ${PM_VERIFY_CACHE})
  set_tests_properties(verification_${pm_case} PROPERTIES TIMEOUT 300 LABELS verification
                       ENVIRONMENT "OMP_NUM_THREADS=1")
endforeach()
