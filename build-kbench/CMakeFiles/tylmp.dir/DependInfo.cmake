
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/main/plugin/core/contact_batch.cpp" "CMakeFiles/tylmp.dir/plugin/core/contact_batch.cpp.o" "gcc" "CMakeFiles/tylmp.dir/plugin/core/contact_batch.cpp.o.d"
  "/work/main/plugin/lammps/compute_thornton_yin_contacts.cpp" "CMakeFiles/tylmp.dir/plugin/lammps/compute_thornton_yin_contacts.cpp.o" "gcc" "CMakeFiles/tylmp.dir/plugin/lammps/compute_thornton_yin_contacts.cpp.o.d"
  "/work/main/plugin/lammps/compute_thornton_yin_micromechanics.cpp" "CMakeFiles/tylmp.dir/plugin/lammps/compute_thornton_yin_micromechanics.cpp.o" "gcc" "CMakeFiles/tylmp.dir/plugin/lammps/compute_thornton_yin_micromechanics.cpp.o.d"
  "/work/main/plugin/lammps/fix_cell_servo.cpp" "CMakeFiles/tylmp.dir/plugin/lammps/fix_cell_servo.cpp.o" "gcc" "CMakeFiles/tylmp.dir/plugin/lammps/fix_cell_servo.cpp.o.d"
  "/work/main/plugin/lammps/fix_damping_cundall.cpp" "CMakeFiles/tylmp.dir/plugin/lammps/fix_damping_cundall.cpp.o" "gcc" "CMakeFiles/tylmp.dir/plugin/lammps/fix_damping_cundall.cpp.o.d"
  "/work/main/plugin/lammps/fix_neigh_history_thornton_yin.cpp" "CMakeFiles/tylmp.dir/plugin/lammps/fix_neigh_history_thornton_yin.cpp.o" "gcc" "CMakeFiles/tylmp.dir/plugin/lammps/fix_neigh_history_thornton_yin.cpp.o.d"
  "/work/main/plugin/lammps/pair_thornton_yin.cpp" "CMakeFiles/tylmp.dir/plugin/lammps/pair_thornton_yin.cpp.o" "gcc" "CMakeFiles/tylmp.dir/plugin/lammps/pair_thornton_yin.cpp.o.d"
  "/work/main/plugin/lammps/tylmp_register.cpp" "CMakeFiles/tylmp.dir/plugin/lammps/tylmp_register.cpp.o" "gcc" "CMakeFiles/tylmp.dir/plugin/lammps/tylmp_register.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
