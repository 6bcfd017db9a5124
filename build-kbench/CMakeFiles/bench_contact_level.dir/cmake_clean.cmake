file(REMOVE_RECURSE
  "CMakeFiles/bench_contact_level.dir/bench/contact_level.cpp.o"
  "CMakeFiles/bench_contact_level.dir/bench/contact_level.cpp.o.d"
  "bench_contact_level"
  "bench_contact_level.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/bench_contact_level.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
