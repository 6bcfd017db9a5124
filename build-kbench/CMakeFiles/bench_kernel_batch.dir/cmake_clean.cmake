file(REMOVE_RECURSE
  "CMakeFiles/bench_kernel_batch.dir/bench/kernel_batch.cpp.o"
  "CMakeFiles/bench_kernel_batch.dir/bench/kernel_batch.cpp.o.d"
  "CMakeFiles/bench_kernel_batch.dir/plugin/core/contact_batch.cpp.o"
  "CMakeFiles/bench_kernel_batch.dir/plugin/core/contact_batch.cpp.o.d"
  "bench_kernel_batch"
  "bench_kernel_batch.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/bench_kernel_batch.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
