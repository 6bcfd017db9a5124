# Benchmark builds of the plugin (included by CMakeLists.txt with -DTYLMP_BENCH=ON; not part of
# the product): the plugin's styles with another definition of the batch law's builds in place
# of plugin/core/contact_batch.cpp. Each says what it is on stderr when loaded.
#   tylmp_plumbing -> build/bench/plumbing/tylmp.so: the law replaced by a Hertz normal force,
#                     everything around it kept (what the plumbing costs)
#   tylmp_generic  -> build/bench/generic/tylmp.so: the adhesive, damped law for every scene
#                     (what the specialisations on Gamma = 0 and no damping gain)
# They replace the vector builds of the law (the scalar build, TYLMP_LAW_ISA=scalar, stays the
# law). Run them with bench/pair_speed.py --variant NAME=build/bench/NAME/tylmp.so.
foreach(_variant plumbing generic)
  set(_source ${CMAKE_SOURCE_DIR}/bench/${_variant}_batch.cpp)
  set_source_files_properties(${_source} PROPERTIES COMPILE_OPTIONS "${TYLMP_LANE_LOOP_OPTIONS}")
  tylmp_plugin_library(tylmp_${_variant} ${_source})
  set_target_properties(tylmp_${_variant} PROPERTIES OUTPUT_NAME tylmp
    LIBRARY_OUTPUT_DIRECTORY "${CMAKE_BINARY_DIR}/bench/${_variant}")
endforeach()

# The SIMD layer chosen by measurement (docs/performance.md, "Seventh round"): the contact law's
# one text on explicit lane types -- std::experimental::simd, xsimd, and Google Highway where
# found -- against the product's builds of advance_batch, one executable per instruction set
# (the layers' width is the compiler target's): build/bench_simd_layers_{sse2,avx2,avx512}.
# x86-64 with GCC's <experimental/simd> and xsimd only; the product's builds of the law
# (plugin/core/contact_batch.cpp) are compiled once, with the product's flags.
include(CheckIncludeFileCXX)
check_include_file_cxx(experimental/simd TYLMP_HAVE_STDX_SIMD)
# header-only (xsimd's CMake package would link xtl, which it does not need)
find_path(TYLMP_XSIMD_INCLUDE xsimd/xsimd.hpp)
find_package(hwy QUIET)
if(CMAKE_SYSTEM_PROCESSOR MATCHES "x86_64|AMD64" AND TYLMP_HAVE_STDX_SIMD AND TYLMP_XSIMD_INCLUDE
   AND TYLMP_VECTOR_LAW)
  add_library(tylmp_bench_batch_law OBJECT ${TYLMP_BATCH_SOURCE})
  target_include_directories(tylmp_bench_batch_law PRIVATE plugin/core)
  target_link_libraries(tylmp_bench_batch_law PRIVATE Eigen3::Eigen)
  set(_isa_flags_sse2 "")
  # what Highway's static AVX2 / AVX-512 targets require of the compiler flags
  set(_isa_flags_avx2 -msse4.2 -mpclmul -maes -mavx2 -mbmi -mbmi2 -mfma -mf16c)
  set(_isa_flags_avx512 ${_isa_flags_avx2} -mavx512f -mavx512bw -mavx512dq -mavx512vl)
  add_custom_target(bench_simd_layers)
  foreach(_isa sse2 avx2 avx512)
    add_executable(bench_simd_layers_${_isa} bench/simd_layers.cpp)
    target_include_directories(bench_simd_layers_${_isa} PRIVATE plugin/core bench
      ${TYLMP_XSIMD_INCLUDE})
    target_compile_definitions(bench_simd_layers_${_isa} PRIVATE TYBENCH_ISA=${_isa})
    target_compile_options(bench_simd_layers_${_isa} PRIVATE -Wall -Wextra -Wno-unused-parameter
      -Wno-parentheses -Wno-uninitialized  # masks with operator!; GCC 12 on its own _mm512_sqrt_pd
      ${TYLMP_LANE_LOOP_OPTIONS} ${_isa_flags_${_isa}})
    target_link_libraries(bench_simd_layers_${_isa} PRIVATE tylmp_bench_batch_law Eigen3::Eigen)
    # Highway 1.0's x86 targets begin at SSSE3 (below, its one-lane scalar target)
    if(hwy_FOUND AND NOT _isa STREQUAL "sse2")
      target_link_libraries(bench_simd_layers_${_isa} PRIVATE hwy::hwy)
    else()
      target_compile_definitions(bench_simd_layers_${_isa} PRIVATE TYBENCH_NO_HWY)
    endif()
    add_dependencies(bench_simd_layers bench_simd_layers_${_isa})
  endforeach()
endif()
