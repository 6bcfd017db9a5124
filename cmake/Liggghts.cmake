# The Thornton-Yin model for Debian's LIGGGHTS 3.8 (plugin/liggghts/): the model library
# libtyliggghts.so, which registers `pair_style gran model thornton_yin tangential thornton_yin`
# into the unmodified libliggghts.so.3 when loaded, and the launcher tyliggghts (the `liggghts`
# command with the model linked in). Built when LIGGGHTS's headers and library are found
# (Debian: apt-get install liggghts libliggghts-dev; the headers of exactly the installed
# library, with Debian's GCC 12 patch); -DTYLMP_LIGGGHTS=OFF skips it, =ON requires it.
set(TYLMP_LIGGGHTS AUTO CACHE STRING "build the LIGGGHTS model and launcher (AUTO: when found)")
find_path(LIGGGHTS_INCLUDE_DIR pair_gran_base.h PATH_SUFFIXES liggghts)
find_library(LIGGGHTS_LIBRARY NAMES liggghts libliggghts.so.3)
if(TYLMP_LIGGGHTS STREQUAL "OFF" OR
   (TYLMP_LIGGGHTS STREQUAL "AUTO" AND (NOT LIGGGHTS_INCLUDE_DIR OR NOT LIGGGHTS_LIBRARY)))
  message(STATUS "tylmp: LIGGGHTS model not built (TYLMP_LIGGGHTS=${TYLMP_LIGGGHTS}; headers: "
    "${LIGGGHTS_INCLUDE_DIR}, library: ${LIGGGHTS_LIBRARY}; apt-get install liggghts libliggghts-dev)")
  return()
endif()
if(NOT LIGGGHTS_INCLUDE_DIR OR NOT LIGGGHTS_LIBRARY)
  message(FATAL_ERROR "tylmp: TYLMP_LIGGGHTS=ON but LIGGGHTS was not found (headers: "
    "${LIGGGHTS_INCLUDE_DIR}, library: ${LIGGGHTS_LIBRARY}): apt-get install liggghts libliggghts-dev")
endif()
# LIGGGHTS's Make.sh writes style_*_model.h, the lists of contact model headers, at its build;
# the -dev package has none. Ours list the models this library compiles: the default surface
# model and the Thornton-Yin pairing
set(_styles "${CMAKE_BINARY_DIR}/liggghts_styles")
file(WRITE "${_styles}/style_surface_model.h" "#include \"surface_model_default.h\"\n")
foreach(_kind normal tangential)
  file(WRITE "${_styles}/style_${_kind}_model.h" "#include \"normal_model_thornton_yin.h\"\n")
endforeach()
foreach(_kind cohesion rolling)
  file(WRITE "${_styles}/style_${_kind}_model.h" "")
endforeach()
add_library(tyliggghts_model SHARED plugin/liggghts/thornton_yin_register.cpp ${TYLMP_BATCH_SOURCE})
target_include_directories(tyliggghts_model PRIVATE plugin/liggghts plugin/core "${_styles}")
# Debian's LIGGGHTS headers as system headers: their own warnings (memset on non-trivial
# structs in pair_gran_base.h) are not ours to print at every build
target_include_directories(tyliggghts_model SYSTEM PRIVATE "${LIGGGHTS_INCLUDE_DIR}")
target_compile_options(tyliggghts_model PRIVATE -Wall -Wno-unused-parameter -fno-math-errno)
target_link_libraries(tyliggghts_model PUBLIC "${LIGGGHTS_LIBRARY}" MPI::MPI_CXX
  PRIVATE Eigen3::Eigen)
# hidden visibility: our instances of LIGGGHTS's inline code never interpose on the library's
set_target_properties(tyliggghts_model PROPERTIES OUTPUT_NAME tyliggghts
  CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON
  LIBRARY_OUTPUT_DIRECTORY "${CMAKE_BINARY_DIR}/liggghts")
add_executable(tyliggghts plugin/liggghts/liggghts_main.cpp)
target_include_directories(tyliggghts PRIVATE "${LIGGGHTS_INCLUDE_DIR}")
# linked although main() names none of its symbols: its static initialiser registers the model
target_link_libraries(tyliggghts PRIVATE -Wl,--no-as-needed tyliggghts_model -Wl,--as-needed)
set_target_properties(tyliggghts PROPERTIES RUNTIME_OUTPUT_DIRECTORY "${CMAKE_BINARY_DIR}/bin"
  BUILD_RPATH "${CMAKE_BINARY_DIR}/liggghts" INSTALL_RPATH "$ORIGIN/../lib")
install(TARGETS tyliggghts_model LIBRARY DESTINATION lib)
install(TARGETS tyliggghts RUNTIME DESTINATION bin)
message(STATUS "tylmp: LIGGGHTS model and launcher (build/bin/tyliggghts) against ${LIGGGHTS_LIBRARY}")
