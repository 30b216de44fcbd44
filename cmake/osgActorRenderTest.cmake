# osgactor_add_render_test(): a CTest that renders a scene offscreen with osgactorrender and compares every frame
# with a reference image (docs/regression-renders.md). Installed beside osgActorConfig.cmake, which includes it;
# osgActor's own tests include it from the source tree.
#
#   find_package(osgActor REQUIRED)
#   osgactor_add_render_test(NAME walk_renders
#       SCENE scenes/walk.osgt                  # any file osgDB reads (.osgt, .ive, .actor, models, ...)
#       REFERENCES references/walk_%04d.png     # one image per frame, %04d the frame number
#       FRAMES 0 47 FPS 24 SIZE 320 240 TOLERANCE 2)
#
# Relative SCENE and REFERENCES paths are from the calling CMakeLists.txt's folder. Optional, besides FRAMES a b
# (default 0 0), FPS f (30), SIZE w h (640 480) and TOLERANCE t (2 of 255):
#   ALLOWED_SHARE p    percent of a frame's pixels that may be over the tolerance (default 0)
#   JOBS n             render in n processes
#   LIBRARY_PATH dirs  folders for OSG_LIBRARY_PATH before osgActor's own (the program's osgDB plugins, or the
#                      libraries holding the classes its .osgt files name)
#   OPTIONS args       more osgactorrender options (--eye x y z, --background r g b, --seed n, --play-animations)
#
# The test passes when every frame matches (exit status 0) and fails when one differs (1) or the scene or a
# reference cannot be read (2). A failing run leaves, in <build>/osgactor_render_tests/<NAME>/, the renders
# (render_%04d.png), a diff image per differing frame (diff_%04d.png), the differing frames side by side
# (comparison.png: reference, render, diff) and every frame's figures (report.csv).
#
# The target update_references_<NAME> (and osgactor_update_references, for every such test) writes the renders
# as the references where they differ or are missing: look at each before committing it.
function(osgactor_add_render_test)
    cmake_parse_arguments(PARSE_ARGV 0 arg "" "NAME;SCENE;REFERENCES;FPS;TOLERANCE;ALLOWED_SHARE;JOBS"
        "FRAMES;SIZE;LIBRARY_PATH;OPTIONS")
    if(arg_UNPARSED_ARGUMENTS)
        message(FATAL_ERROR "osgactor_add_render_test: unknown arguments: ${arg_UNPARSED_ARGUMENTS}")
    endif()
    foreach(required NAME SCENE REFERENCES)
        if(NOT arg_${required})
            message(FATAL_ERROR "osgactor_add_render_test: ${required} is missing")
        endif()
    endforeach()
    if(NOT TARGET osgActor::osgactorrender)
        message(FATAL_ERROR "osgactor_add_render_test(${arg_NAME}): osgActor::osgactorrender is not there "
            "(osgActor built without its applications?)")
    endif()
    list(LENGTH arg_FRAMES num_frame_values)
    list(LENGTH arg_SIZE num_size_values)
    if((DEFINED arg_FRAMES AND NOT num_frame_values EQUAL 2) OR (DEFINED arg_SIZE AND NOT num_size_values EQUAL 2))
        message(FATAL_ERROR "osgactor_add_render_test(${arg_NAME}): FRAMES and SIZE take two numbers each")
    endif()

    get_filename_component(scene "${arg_SCENE}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
    get_filename_component(references "${arg_REFERENCES}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
    set(out "${CMAKE_CURRENT_BINARY_DIR}/osgactor_render_tests/${arg_NAME}")

    set(render_options "${scene}")
    # Each keyword is the osgactorrender option of its name (ALLOWED_SHARE: --allowed-share). DEFINED, not the
    # value's truth: 0 is a value (TOLERANCE 0, FRAMES 0 0).
    foreach(keyword FRAMES FPS SIZE TOLERANCE ALLOWED_SHARE JOBS)
        if(DEFINED arg_${keyword})
            string(TOLOWER "${keyword}" option)
            string(REPLACE "_" "-" option "${option}")
            list(APPEND render_options --${option} ${arg_${keyword}})
        endif()
    endforeach()
    list(APPEND render_options ${arg_OPTIONS} --compare "${references}")

    # osgDB finds plugins (osgPlugins-<version>/ below each folder) and the libraries of serialized classes on
    # OSG_LIBRARY_PATH: the program's folders first, then where the osgActor libraries are.
    set(library_path ${arg_LIBRARY_PATH} "$<TARGET_FILE_DIR:osgActor::Offscreen>")
    string(REPLACE ";" ":" library_path "${library_path}")

    add_test(NAME ${arg_NAME}
        COMMAND osgActor::osgactorrender ${render_options} -o "${out}/render_%04d.png"
            --diff "${out}/diff_%04d.png" --compare-sheet "${out}/comparison.png" --report "${out}/report.csv")
    set_tests_properties(${arg_NAME} PROPERTIES
        ENVIRONMENT "OSG_LIBRARY_PATH=${library_path};OSG_NOTIFY_LEVEL=WARN"
        LABELS osgactor_render)

    add_custom_target(update_references_${arg_NAME}
        COMMAND "${CMAKE_COMMAND}" -E env "OSG_LIBRARY_PATH=${library_path}" OSG_NOTIFY_LEVEL=WARN
            "$<TARGET_FILE:osgActor::osgactorrender>" ${render_options} --update-references
        COMMENT "osgactorrender: references of ${arg_NAME} (look at every image it writes before committing it)"
        VERBATIM)
    if(NOT TARGET osgactor_update_references)
        add_custom_target(osgactor_update_references)
    endif()
    add_dependencies(osgactor_update_references update_references_${arg_NAME})
endfunction()
