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
