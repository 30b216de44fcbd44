# Helpers shared by every target of the project.

# Warnings every target of ours is built with.
function(osgactor_set_warnings target)
    target_compile_options(${target} PRIVATE -Wall -Wextra)
    if(OSGACTOR_WARNINGS_AS_ERRORS)
        target_compile_options(${target} PRIVATE -Werror)
    endif()
endfunction()

# An osgDB plugin: a MODULE library named osgdb_<name>, no "lib" prefix, placed where osgDB's own lookup finds it
# (build/lib/osgPlugins-<ver>/ in the build tree, <libdir>/osgPlugins-<ver>/ once installed).
function(osgactor_add_plugin name)
    set(target osgdb_${name})
    add_library(${target} MODULE ${ARGN})
    set_target_properties(${target} PROPERTIES
        PREFIX ""
        LIBRARY_OUTPUT_DIRECTORY "${OSGACTOR_PLUGIN_OUTPUT_DIRECTORY}"
        INSTALL_RPATH "${OSGACTOR_PLUGIN_INSTALL_RPATH}")
    target_link_libraries(${target} PRIVATE osgActor)
    osgactor_set_warnings(${target})
    install(TARGETS ${target} LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}/${OSGACTOR_PLUGIN_DIR_NAME}")
endfunction()
