# Finds every external dependency (all Debian 12 packages; scripts/install-deps.sh installs them).
# See ../shared/TOOLING.md for why each call looks the way it does.

find_package(Eigen3 3.4 REQUIRED NO_MODULE)
# Spectra (header-only): Lanczos eigenpairs of the tangent at unstable equilibria (lowest_modes).
find_package(spectra 1.0 REQUIRED CONFIG)

# OpenCASCADE: listing only DataExchange fails with missing targets; its targets carry no include dirs.
find_package(OpenCASCADE REQUIRED COMPONENTS FoundationClasses ModelingData ModelingAlgorithms
             Visualization ApplicationFramework DataExchange)
add_library(isomuscle_occt INTERFACE)
target_include_directories(isomuscle_occt SYSTEM INTERFACE ${OpenCASCADE_INCLUDE_DIR})
target_link_libraries(isomuscle_occt INTERFACE TKIGES TKXSBase TKShHealing TKTopAlgo TKGeomAlgo
                      TKBRep TKGeomBase TKG3d TKG2d TKMath TKernel)

# SuiteSparse ships no CMake config in Debian 12.
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
find_library(CHOLMOD_LIBRARY cholmod REQUIRED)
find_library(UMFPACK_LIBRARY umfpack REQUIRED)
find_library(AMD_LIBRARY amd REQUIRED)
find_library(COLAMD_LIBRARY colamd REQUIRED)
find_library(SUITESPARSECONFIG_LIBRARY suitesparseconfig REQUIRED)
add_library(isomuscle_suitesparse INTERFACE)
target_include_directories(isomuscle_suitesparse SYSTEM INTERFACE ${CHOLMOD_INCLUDE_DIR})
target_link_libraries(isomuscle_suitesparse INTERFACE ${CHOLMOD_LIBRARY} ${UMFPACK_LIBRARY}
                      ${AMD_LIBRARY} ${COLAMD_LIBRARY} ${SUITESPARSECONFIG_LIBRARY})

find_package(HDF5 REQUIRED COMPONENTS C)

find_path(GMSH_INCLUDE_DIR gmsh.h REQUIRED)
find_library(GMSH_LIBRARY gmsh REQUIRED)
add_library(isomuscle_gmsh INTERFACE)
target_include_directories(isomuscle_gmsh SYSTEM INTERFACE ${GMSH_INCLUDE_DIR})
target_link_libraries(isomuscle_gmsh INTERFACE ${GMSH_LIBRARY})

find_package(tomlplusplus REQUIRED)
find_package(CLI11 REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(GTest REQUIRED)
find_package(OpenMP REQUIRED COMPONENTS CXX)
if(ISOMUSCLE_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()

# One library per source folder, made from every .cpp in it (so parallel work on a folder never
# edits a shared list). A folder without sources yet becomes an interface library.
function(isomuscle_folder_library folder)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp)
  set(target isomuscle_${folder})
  if(sources)
    add_library(${target} STATIC ${sources})
    target_include_directories(${target} PUBLIC ${PROJECT_SOURCE_DIR} ${PROJECT_BINARY_DIR}/generated)
    target_link_libraries(${target} PUBLIC ${ARG_DEPS})
  else()
    add_library(${target} INTERFACE)
    target_include_directories(${target} INTERFACE ${PROJECT_SOURCE_DIR} ${PROJECT_BINARY_DIR}/generated)
    target_link_libraries(${target} INTERFACE ${ARG_DEPS})
  endif()
endfunction()
