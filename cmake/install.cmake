# Install rules and the CMake package of polydual (included by the top-level
# CMakeLists.txt after lib/). `cmake --install build --prefix P` gives
#   P/bin/polydual                                the command
#   P/lib/polydual/polydual-gmsh.so               its Gmsh module (generate, demo; dlopen)
#   P/lib/polydual/polydual-lbfgs.so              its Ceres L-BFGS module (--optimize global; dlopen)
#   P/lib/libpolydual_core.a                      polydual::polydual
#   P/lib/libpolydual_generate.a                  polydual::generate (component "generate", needs libgmsh)
#   P/include/polydual/<core|mesh|io|...>/*.h     lib/ without cli/ and alloc/
#   P/lib/cmake/polydual/polydual-config.cmake    find_package(polydual CONFIG [COMPONENTS generate])
#   P/lib/cmake/polydual/polydual-config-version.cmake, polydual-targets*.cmake,
#     polydual-generate-targets*.cmake
# The headers include each other relative to lib/ ("core/error.h"), so the
# package's include directory is P/include/polydual.
include(CMakePackageConfigHelpers)
set(POLYDUAL_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/polydual)

install(TARGETS polydual RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# Where the command looks for them (lib/core/module_loader.h).
install(TARGETS polydual_gmsh polydual_lbfgs LIBRARY DESTINATION ${POLYDUAL_GMSH_MODULE_DIR})
install(TARGETS polydual_core EXPORT polydual-targets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS polydual_generate EXPORT polydual-generate-targets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
# lib/cli (the command) and lib/alloc (a replacement of the global operator
# new, for executables only) are not part of the library.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/lib/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/polydual
  FILES_MATCHING PATTERN "*.h"
  PATTERN "cli" EXCLUDE
  PATTERN "alloc" EXCLUDE
  PATTERN "module_loader.h" EXCLUDE)  # built into the command only
install(EXPORT polydual-targets NAMESPACE polydual:: FILE polydual-targets.cmake
  DESTINATION ${POLYDUAL_CMAKE_DIR})
install(EXPORT polydual-generate-targets NAMESPACE polydual:: FILE polydual-generate-targets.cmake
  DESTINATION ${POLYDUAL_CMAKE_DIR})

# How a consumer finds the package behind each namespace of an imported target
# that lib/ links (the same modes as the top-level find_package calls; CGAL's
# config finds GMP, MPFR and Boost itself).
set(_polydual_package_CGAL "CGAL CONFIG")
set(_polydual_package_Ceres "Ceres CONFIG")
set(_polydual_package_Eigen3 "Eigen3 CONFIG")
set(_polydual_package_TBB "TBB CONFIG")
set(_polydual_package_Boost "Boost")
set(_polydual_package_ZLIB "ZLIB")
set(_polydual_package_Threads "Threads")

# polydual_dependencies(target lines_var targets_var): the find_dependency()
# lines for the imported targets `target` links, and those targets. A target
# from a namespace missing above stops the configuration (else the installed
# package would name a target no consumer can resolve). gmsh::gmsh is made by
# the config file itself.
function(polydual_dependencies target lines_var targets_var)
  get_target_property(libs ${target} INTERFACE_LINK_LIBRARIES)
  set(lines "")
  set(targets "")
  foreach(lib IN LISTS libs)
    string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" lib "${lib}")
    if(lib MATCHES "^polydual_" OR lib STREQUAL "gmsh::gmsh")
      continue()
    endif()
    if(lib MATCHES "^([A-Za-z0-9_]+)::")
      set(ns ${CMAKE_MATCH_1})
      if(NOT DEFINED _polydual_package_${ns})
        message(FATAL_ERROR "${target} links ${lib}: add the package providing `${ns}::` targets "
                            "to the table in cmake/install.cmake so that installed consumers find it")
      endif()
      list(APPEND lines "find_dependency(${_polydual_package_${ns}})")
      list(APPEND targets ${lib})
    elseif(lib MATCHES "\\$<")
      message(FATAL_ERROR "${target} links `${lib}`: cmake/install.cmake cannot translate this "
                          "generator expression into a find_dependency() for the installed package")
    endif()
    # Plain names and absolute paths are exported as they are.
  endforeach()
  list(REMOVE_DUPLICATES lines)
  list(JOIN lines "\n" text)
  set(${lines_var} "${text}" PARENT_SCOPE)
  set(${targets_var} "${targets}" PARENT_SCOPE)
endfunction()

polydual_dependencies(polydual_core POLYDUAL_CORE_DEPENDENCIES POLYDUAL_CORE_DEPENDENCY_TARGETS)
polydual_dependencies(polydual_generate POLYDUAL_GENERATE_DEPENDENCIES POLYDUAL_GENERATE_DEPENDENCY_TARGETS)
get_filename_component(POLYDUAL_GMSH_LIBRARY_DIR "${GMSH_LIBRARY}" DIRECTORY)

configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/polydual-config.cmake.in
  ${PROJECT_BINARY_DIR}/polydual-config.cmake INSTALL_DESTINATION ${POLYDUAL_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/polydual-config-version.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/polydual-config.cmake ${PROJECT_BINARY_DIR}/polydual-config-version.cmake
  DESTINATION ${POLYDUAL_CMAKE_DIR})
