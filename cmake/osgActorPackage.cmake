# What osgActor installs and how others find it: the install layout's run paths, the OpenSceneGraph interface target,
# the CMake package (osgActorConfig.cmake), the pkg-config file (osgActor.pc) and the Debian package (cpack -G DEB).
# Included by the top-level CMakeLists.txt before any target (the run paths and the OSG target), which calls
# osgactor_install_package() once every target exists. README.md, "Using osgActor from your project".

# --- Run paths of installed binaries ------------------------------------------------------------------------------
# Installed under a prefix the dynamic linker does not search (/usr/local, a home folder, a test's temporary prefix),
# the tools find libosgActor, and the plugins find it when a program that does not link it (osgviewer) loads them,
# through a path relative to where they lie. Under /usr the system's search suffices and nothing is added.
list(FIND CMAKE_CXX_IMPLICIT_LINK_DIRECTORIES "${CMAKE_INSTALL_FULL_LIBDIR}" _osgactor_libdir_is_system)
if(_osgactor_libdir_is_system EQUAL -1)
    file(RELATIVE_PATH _osgactor_bin_to_lib "/${CMAKE_INSTALL_BINDIR}" "/${CMAKE_INSTALL_LIBDIR}")
    set(CMAKE_INSTALL_RPATH "$ORIGIN/${_osgactor_bin_to_lib}")
    # Plugins lie one folder below the library (osgactor_add_plugin() in osgActorMacros.cmake).
    set(OSGACTOR_PLUGIN_INSTALL_RPATH "$ORIGIN/..")
endif()

# --- OpenSceneGraph as targets ------------------------------------------------------------------------------------
# CMake's FindOpenSceneGraph gives paths, not targets. Our libraries' interfaces name targets made here instead of those
# paths, so that, installed, osgActorConfig.cmake fills them with the OpenSceneGraph the consumer's own find_package()
# finds, not with this machine's paths.
# osgactor_openscenegraph_target(<target> <export name> <components...>): an INTERFACE target for those components (osg
# and OpenThreads come with any), installed as osgActor::<export name>.
function(osgactor_openscenegraph_target target export_name)
    set(libraries)
    foreach(component ${ARGN})
        string(TOUPPER "${component}" upper)
        list(APPEND libraries ${${upper}_LIBRARIES})
    endforeach()
    list(APPEND libraries ${OSG_LIBRARIES} ${OPENTHREADS_LIBRARIES})
    add_library(${target} INTERFACE)
    set_target_properties(${target} PROPERTIES EXPORT_NAME ${export_name})
    target_include_directories(${target} INTERFACE "$<BUILD_INTERFACE:${OPENSCENEGRAPH_INCLUDE_DIRS}>")
    target_link_libraries(${target} INTERFACE "$<BUILD_INTERFACE:${libraries}>")
    install(TARGETS ${target} EXPORT osgActorTargets)
    string(REPLACE ";" "," components "${ARGN}")
    set_property(GLOBAL APPEND PROPERTY OSGACTOR_OSG_TARGETS "${export_name}:${components}")
endfunction()
# libosgActor's: what its public headers and the library use.
set(OSGACTOR_OSG_INTERFACE_COMPONENTS osgDB osgUtil)
osgactor_openscenegraph_target(osgActorOpenSceneGraph OpenSceneGraph ${OSGACTOR_OSG_INTERFACE_COMPONENTS})

# --- Helpers consumers get from find_package(osgActor) --------------------------------------------------------------
# osgactor_install_config_module(<file.cmake>): installs a CMake file beside osgActorConfig.cmake, which includes it
# after the targets, so that functions it defines are there for consumers as for this project.
function(osgactor_install_config_module file)
    get_filename_component(path "${file}" ABSOLUTE)
    get_filename_component(name "${file}" NAME)
    install(FILES "${path}" DESTINATION "${CMAKE_INSTALL_LIBDIR}/cmake/osgActor")
    set_property(GLOBAL APPEND PROPERTY OSGACTOR_CONFIG_MODULES "${name}")
endfunction()

# --- Everything else, once the targets exist ------------------------------------------------------------------------
function(osgactor_install_package)
    set(config_dir "${CMAKE_INSTALL_LIBDIR}/cmake/osgActor")
    set(OSGACTOR_SUMMARY "OpenSceneGraph nodekit for synthetic actors: skeletons, DOFs, motion capture, clips, IK")
    get_property(OSGACTOR_CONFIG_MODULES GLOBAL PROPERTY OSGACTOR_CONFIG_MODULES)
    get_property(OSGACTOR_OSG_TARGETS GLOBAL PROPERTY OSGACTOR_OSG_TARGETS)

    # The CMake package: find_package(osgActor) gives osgActor::osgActor (osgActorConfig.cmake.in).
    include(CMakePackageConfigHelpers)
    configure_package_config_file("${PROJECT_SOURCE_DIR}/cmake/osgActorConfig.cmake.in"
        "${PROJECT_BINARY_DIR}/osgActorConfig.cmake" INSTALL_DESTINATION "${config_dir}")
    write_basic_package_version_file("${PROJECT_BINARY_DIR}/osgActorConfigVersion.cmake"
        COMPATIBILITY SameMinorVersion)
    install(EXPORT osgActorTargets NAMESPACE osgActor:: DESTINATION "${config_dir}")
    install(FILES "${PROJECT_BINARY_DIR}/osgActorConfig.cmake" "${PROJECT_BINARY_DIR}/osgActorConfigVersion.cmake"
        DESTINATION "${config_dir}")

    # The pkg-config file, beside OSG's own (<libdir>/pkgconfig). Its prefix is found from where the file lies, so
    # the same file serves an install under any prefix (cmake --install --prefix) and a Debian package's /usr.
    file(RELATIVE_PATH OSGACTOR_PC_TO_PREFIX "/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/")
    string(REGEX REPLACE "/$" "" OSGACTOR_PC_TO_PREFIX "${OSGACTOR_PC_TO_PREFIX}")
    set(OSGACTOR_PC_REQUIRES "openthreads openscenegraph-osg")
    foreach(component ${OSGACTOR_OSG_INTERFACE_COMPONENTS})
        string(APPEND OSGACTOR_PC_REQUIRES " openscenegraph-${component}")
    endforeach()
    string(APPEND OSGACTOR_PC_REQUIRES " glm")
    configure_file("${PROJECT_SOURCE_DIR}/cmake/osgActor.pc.in" "${PROJECT_BINARY_DIR}/osgActor.pc" @ONLY)
    install(FILES "${PROJECT_BINARY_DIR}/osgActor.pc" DESTINATION "${CMAKE_INSTALL_LIBDIR}/pkgconfig")

    # The Debian package: cpack -G DEB in the build folder. One package with everything the install holds
    # (library, headers, plugins, tools, CMake and pkg-config files), installing under /usr; the libraries it runs
    # on come from dpkg-shlibdeps, the headers a consumer compiles against from the -dev packages named here.
    set(CPACK_PACKAGE_NAME "osgactor")
    set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
    set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${OSGACTOR_SUMMARY}")
    set(OSGACTOR_PACKAGE_CONTACT "osgActor maintainers" CACHE STRING "Maintainer field of the Debian package")
    set(CPACK_PACKAGE_CONTACT "${OSGACTOR_PACKAGE_CONTACT}")
    set(CPACK_PACKAGING_INSTALL_PREFIX "/usr")
    set(CPACK_STRIP_FILES ON)
    set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
    set(CPACK_DEBIAN_PACKAGE_SECTION "libdevel")
    set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
    set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS "${PROJECT_BINARY_DIR}/lib")
    set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)
    # libosmesa6-dev: osgActor::Offscreen's users link libOSMesa.so first (osgActor/Offscreen/CMakeLists.txt).
    set(CPACK_DEBIAN_PACKAGE_DEPENDS "libopenscenegraph-dev (>= 3.6), libglm-dev, libosmesa6-dev")
    set(CPACK_GENERATOR "DEB")
    include(CPack)
endfunction()
