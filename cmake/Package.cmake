# kdop as a CMake package, from its build tree and from an installation.
#
# Both provide kdop::kdop-gen, kdop::variant_headers and kdop_add_variants() (cmake/KdopVariants.cmake),
# and a version file: find_package(kdop 0.1) accepts 0.1.x only, as a 0.x release may change the API.
# The installed package is relocatable: every path in it is relative to the config file. The
# installation also carries lib/pkgconfig/kdop.pc (cmake/kdop.pc.in) for Meson and Makefiles,
# relocatable the same way through ${pcfiledir}.
include(CMakePackageConfigHelpers)
include(GNUInstallDirs)

set(KDOP_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/kdop)
set(KDOP_INSTALL_AXIS_SET_DIR ${CMAKE_INSTALL_DATADIR}/kdop/axis_sets)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/kdopConfigVersion.cmake COMPATIBILITY SameMinorVersion)

# Build tree: -Dkdop_DIR=<kdop build dir>. It refers to the source tree, as a build tree does.
export(TARGETS kdop-gen kdop_variant_headers NAMESPACE kdop:: FILE ${PROJECT_BINARY_DIR}/kdopTargets.cmake)
set(KDOP_CONFIG_AXIS_SET_DIR ${PROJECT_SOURCE_DIR}/shader_templates/axis_sets)
set(KDOP_CONFIG_VARIANTS_MODULE ${PROJECT_SOURCE_DIR}/cmake/KdopVariants.cmake)
set(KDOP_CONFIG_SHADER_LANGUAGES_FILE ${PROJECT_SOURCE_DIR}/generator/shader_languages.def)
configure_file(${PROJECT_SOURCE_DIR}/cmake/kdopConfig.cmake.in ${PROJECT_BINARY_DIR}/kdopConfig.cmake @ONLY)

# Installation: cmake --install <build> [--prefix P], then find_package(kdop) with P on CMAKE_PREFIX_PATH.
set(installed_programs kdop-gen)
if(TARGET kdop)
  list(APPEND installed_programs kdop)
endif()
install(TARGETS ${installed_programs} kdop_variant_headers EXPORT kdopTargets
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
if(TARGET kdop)
  # kdop's image codecs, which it loads on first use from <bindir>/../<libdir>/kdop (images/image_codecs.h).
  install(TARGETS kdop_image_codecs LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/kdop)
endif()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/core/include/kdop DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/shader_templates/axis_sets/ DESTINATION ${KDOP_INSTALL_AXIS_SET_DIR}
        FILES_MATCHING PATTERN "*.axes")
# The default variants' functions and compute shaders, as generated/ holds them (checked fresh by
# the tests), so a user of the installed package can include one without running kdop gen.
kdop_shader_language_extensions(function_extensions)
set(function_patterns PATTERN "*.comp")
foreach(extension IN LISTS function_extensions)
  list(APPEND function_patterns PATTERN "*.${extension}")
endforeach()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/generated/ DESTINATION ${CMAKE_INSTALL_DATADIR}/kdop/functions
        FILES_MATCHING ${function_patterns})
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/NOTICE DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(EXPORT kdopTargets NAMESPACE kdop:: DESTINATION ${KDOP_INSTALL_CMAKEDIR})
# configure_package_config_file turns the install paths into paths relative to the config file.
set(KDOP_CONFIG_AXIS_SET_DIR "\${PACKAGE_PREFIX_DIR}/${KDOP_INSTALL_AXIS_SET_DIR}")
set(KDOP_CONFIG_VARIANTS_MODULE "\${CMAKE_CURRENT_LIST_DIR}/KdopVariants.cmake")
set(KDOP_CONFIG_SHADER_LANGUAGES_FILE "\${CMAKE_CURRENT_LIST_DIR}/shader_languages.def")
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/kdopConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/install/kdopConfig.cmake
                              INSTALL_DESTINATION ${KDOP_INSTALL_CMAKEDIR})
# pkg-config: the prefix as the .pc file's folder reaches it (lib/pkgconfig, or lib/<triplet>/pkgconfig).
set(KDOP_INSTALL_PKGCONFIGDIR ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
file(RELATIVE_PATH KDOP_PC_PREFIX_FROM_PCFILEDIR /prefix/${KDOP_INSTALL_PKGCONFIGDIR} /prefix)
configure_file(${PROJECT_SOURCE_DIR}/cmake/kdop.pc.in ${PROJECT_BINARY_DIR}/install/kdop.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/install/kdop.pc DESTINATION ${KDOP_INSTALL_PKGCONFIGDIR})
install(FILES ${PROJECT_BINARY_DIR}/install/kdopConfig.cmake ${PROJECT_BINARY_DIR}/kdopConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/KdopVariants.cmake ${PROJECT_SOURCE_DIR}/generator/shader_languages.def
        DESTINATION ${KDOP_INSTALL_CMAKEDIR})
