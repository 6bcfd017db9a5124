
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/main/plugin/core/contact_batch.cpp" "CMakeFiles/core_tests.dir/plugin/core/contact_batch.cpp.o" "gcc" "CMakeFiles/core_tests.dir/plugin/core/contact_batch.cpp.o.d"
  "/work/main/tests/core/test_cell_servo.cpp" "CMakeFiles/core_tests.dir/tests/core/test_cell_servo.cpp.o" "gcc" "CMakeFiles/core_tests.dir/tests/core/test_cell_servo.cpp.o.d"
  "/work/main/tests/core/test_cell_statistics.cpp" "CMakeFiles/core_tests.dir/tests/core/test_cell_statistics.cpp.o" "gcc" "CMakeFiles/core_tests.dir/tests/core/test_cell_statistics.cpp.o.d"
  "/work/main/tests/core/test_contact_batch.cpp" "CMakeFiles/core_tests.dir/tests/core/test_contact_batch.cpp.o" "gcc" "CMakeFiles/core_tests.dir/tests/core/test_contact_batch.cpp.o.d"
  "/work/main/tests/core/test_contact_kernel.cpp" "CMakeFiles/core_tests.dir/tests/core/test_contact_kernel.cpp.o" "gcc" "CMakeFiles/core_tests.dir/tests/core/test_contact_kernel.cpp.o.d"
  "/work/main/tests/core/test_csv_record.cpp" "CMakeFiles/core_tests.dir/tests/core/test_csv_record.cpp.o" "gcc" "CMakeFiles/core_tests.dir/tests/core/test_csv_record.cpp.o.d"
  "/work/main/tests/core/test_fast_numerics.cpp" "CMakeFiles/core_tests.dir/tests/core/test_fast_numerics.cpp.o" "gcc" "CMakeFiles/core_tests.dir/tests/core/test_fast_numerics.cpp.o.d"
  "/work/main/tests/core/test_hertz_lattice.cpp" "CMakeFiles/core_tests.dir/tests/core/test_hertz_lattice.cpp.o" "gcc" "CMakeFiles/core_tests.dir/tests/core/test_hertz_lattice.cpp.o.d"
  "/work/main/tests/core/test_jkr.cpp" "CMakeFiles/core_tests.dir/tests/core/test_jkr.cpp.o" "gcc" "CMakeFiles/core_tests.dir/tests/core/test_jkr.cpp.o.d"
  "/work/main/tests/core/test_law_domain.cpp" "CMakeFiles/core_tests.dir/tests/core/test_law_domain.cpp.o" "gcc" "CMakeFiles/core_tests.dir/tests/core/test_law_domain.cpp.o.d"
  "/work/main/tests/core/test_local_damping.cpp" "CMakeFiles/core_tests.dir/tests/core/test_local_damping.cpp.o" "gcc" "CMakeFiles/core_tests.dir/tests/core/test_local_damping.cpp.o.d"
  "/work/main/tests/core/test_mindlin_deresiewicz.cpp" "CMakeFiles/core_tests.dir/tests/core/test_mindlin_deresiewicz.cpp.o" "gcc" "CMakeFiles/core_tests.dir/tests/core/test_mindlin_deresiewicz.cpp.o.d"
  "/work/main/tests/core/test_pi_plane.cpp" "CMakeFiles/core_tests.dir/tests/core/test_pi_plane.cpp.o" "gcc" "CMakeFiles/core_tests.dir/tests/core/test_pi_plane.cpp.o.d"
  "/work/main/tests/core/test_strain_path.cpp" "CMakeFiles/core_tests.dir/tests/core/test_strain_path.cpp.o" "gcc" "CMakeFiles/core_tests.dir/tests/core/test_strain_path.cpp.o.d"
  "/work/main/tests/core/test_thornton_yin.cpp" "CMakeFiles/core_tests.dir/tests/core/test_thornton_yin.cpp.o" "gcc" "CMakeFiles/core_tests.dir/tests/core/test_thornton_yin.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
