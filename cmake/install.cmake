# `cmake --install BUILD [--prefix P]`: the emcontact binary, the public headers
# (include/emcontact/..., include/kernels/<name>.hpp), the plot script Output/plot runs
# (share/emcontact/plot_monitors.py), the module libraries and the CMake package
# emcontact (lib/cmake/emcontact: emcontactConfig.cmake, emcontactConfigVersion.cmake and the
# targets emcontact::core, emcontact::kernels, emcontact::emc_<module>), so that another project
# can find_package(emcontact) (docs/developer-guide.md, "Installing and using emcontact from
# CMake"). Included by the top-level CMakeLists.txt after the targets.
include(CMakePackageConfigHelpers)
set(EMC_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/emcontact)
set(EMC_MODULES base input mesh fem linalg contact time output os app)
list(TRANSFORM EMC_MODULES PREPEND emc_ OUTPUT_VARIABLE EMC_MODULE_TARGETS)

install(TARGETS emcontact RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(PROGRAMS tools/plot_monitors.py DESTINATION ${CMAKE_INSTALL_DATADIR}/emcontact)
install(TARGETS ${EMC_MODULE_TARGETS} emcontact_core emcontact_kernels emc_kernels emc_deps
                emc_kokkos emc_hdf5 emc_gmsh
        EXPORT emcontactTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY include/emcontact DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING
        PATTERN "*.hpp")
install(EXPORT emcontactTargets NAMESPACE emcontact:: DESTINATION ${EMC_INSTALL_CMAKEDIR})

# The config finds the same Trilinos components (EMC_TRILINOS_COMPONENTS) in the consumer's
# project, and OpenMP where Kokkos has it.
if(EMC_KOKKOS_OPENMP)
  set(EMC_CONFIG_OPENMP TRUE)
else()
  set(EMC_CONFIG_OPENMP FALSE)
endif()
configure_package_config_file(cmake/emcontactConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/cmake/emcontactConfig.cmake
                              INSTALL_DESTINATION ${EMC_INSTALL_CMAKEDIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/cmake/emcontactConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/cmake/emcontactConfig.cmake
              ${CMAKE_BINARY_DIR}/cmake/emcontactConfigVersion.cmake
        DESTINATION ${EMC_INSTALL_CMAKEDIR})
