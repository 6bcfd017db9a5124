file(REMOVE_RECURSE
  "CMakeFiles/tylmp.dir/plugin/core/contact_batch.cpp.o"
  "CMakeFiles/tylmp.dir/plugin/core/contact_batch.cpp.o.d"
  "CMakeFiles/tylmp.dir/plugin/lammps/compute_thornton_yin_contacts.cpp.o"
  "CMakeFiles/tylmp.dir/plugin/lammps/compute_thornton_yin_contacts.cpp.o.d"
  "CMakeFiles/tylmp.dir/plugin/lammps/compute_thornton_yin_micromechanics.cpp.o"
  "CMakeFiles/tylmp.dir/plugin/lammps/compute_thornton_yin_micromechanics.cpp.o.d"
  "CMakeFiles/tylmp.dir/plugin/lammps/fix_cell_servo.cpp.o"
  "CMakeFiles/tylmp.dir/plugin/lammps/fix_cell_servo.cpp.o.d"
  "CMakeFiles/tylmp.dir/plugin/lammps/fix_damping_cundall.cpp.o"
  "CMakeFiles/tylmp.dir/plugin/lammps/fix_damping_cundall.cpp.o.d"
  "CMakeFiles/tylmp.dir/plugin/lammps/fix_neigh_history_thornton_yin.cpp.o"
  "CMakeFiles/tylmp.dir/plugin/lammps/fix_neigh_history_thornton_yin.cpp.o.d"
  "CMakeFiles/tylmp.dir/plugin/lammps/pair_thornton_yin.cpp.o"
  "CMakeFiles/tylmp.dir/plugin/lammps/pair_thornton_yin.cpp.o.d"
  "CMakeFiles/tylmp.dir/plugin/lammps/tylmp_register.cpp.o"
  "CMakeFiles/tylmp.dir/plugin/lammps/tylmp_register.cpp.o.d"
  "python/tylmp/tylmp-20210929.pdb"
  "python/tylmp/tylmp-20210929.so"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/tylmp.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
