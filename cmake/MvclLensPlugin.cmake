# Building lens plugins, in this tree and against an installed mvcl (find_package(mvcl) includes
# this file). See docs/writing-a-lens.md.
#
#   mvcl_add_lens_plugin(<name> SOURCES <file>... [OUTPUT_DIRECTORY <dir>] [NO_INSTALL])
#
#     Builds the module mvcl-lens-<name>.so (no "lib" prefix: the loader looks for mvcl-lens-*.so)
#     linked to mvcl::mvcl, with hidden visibility: the only exported symbol is the entry point
#     that MVCL_LENS_PLUGIN(...) marks visible itself. The module goes to OUTPUT_DIRECTORY, else
#     to ${MVCL_LENS_PLUGIN_OUTPUT_DIRECTORY} when set (this tree sets it to <build>/lib/mvcl/plugins,
#     which <build>/bin/../lib/mvcl/plugins finds), else to CMake's default library directory.
#     Unless NO_INSTALL, it installs to ${MVCL_LENS_PLUGIN_INSTALL_DIR} (lib/mvcl/plugins, relative
#     to the install prefix), which an installed mvcl app finds as <exe dir>/../lib/mvcl/plugins.
#     Plugins need no RPATH: they are only ever loaded by libmvcl, which is therefore loaded.
#
#   mvcl_add_static_lens(<target> <id> SOURCES <file>...)
#
#     Compiles the same plugin source into an OBJECT library with MVCL_LENS_STATIC_ID=<id>, so its
#     entry is the C function mvcl_lens_plugin_<id>. Link <target> into an app and register it
#     explicitly:  extern "C" const MvclLensPluginEntry *mvcl_lens_plugin_<id>();
#                  registry.add(mvcl_lens_plugin_<id>());

include_guard(GLOBAL)

# Fixed rather than ${CMAKE_INSTALL_LIBDIR}/...: on Debian with prefix /usr GNUInstallDirs picks
# lib/x86_64-linux-gnu, and the loader's <exe dir>/../lib/mvcl/plugins must not depend on that.
if(NOT DEFINED MVCL_LENS_PLUGIN_INSTALL_DIR)
    set(MVCL_LENS_PLUGIN_INSTALL_DIR lib/mvcl/plugins)
endif()

function(mvcl_add_lens_plugin name)
    cmake_parse_arguments(PARSE_ARGV 1 arg "NO_INSTALL" "OUTPUT_DIRECTORY" "SOURCES")
    if(arg_UNPARSED_ARGUMENTS OR NOT arg_SOURCES)
        message(FATAL_ERROR "usage: mvcl_add_lens_plugin(<name> SOURCES <file>... [OUTPUT_DIRECTORY <dir>] [NO_INSTALL])")
    endif()
    set(target mvcl-lens-${name})
    add_library(${target} MODULE ${arg_SOURCES})
    target_link_libraries(${target} PRIVATE mvcl::mvcl)
    target_compile_features(${target} PRIVATE cxx_std_20)
    set_target_properties(${target} PROPERTIES
        PREFIX ""
        SUFFIX ".so"
        CXX_VISIBILITY_PRESET hidden
        VISIBILITY_INLINES_HIDDEN ON)
    if(arg_OUTPUT_DIRECTORY)
        set_target_properties(${target} PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${arg_OUTPUT_DIRECTORY})
    elseif(DEFINED MVCL_LENS_PLUGIN_OUTPUT_DIRECTORY)
        set_target_properties(${target} PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${MVCL_LENS_PLUGIN_OUTPUT_DIRECTORY})
    endif()
    if(NOT arg_NO_INSTALL)
        install(TARGETS ${target} LIBRARY DESTINATION ${MVCL_LENS_PLUGIN_INSTALL_DIR})
        # Lets a project build "every installable plugin" (add_dependencies on this list).
        set_property(GLOBAL APPEND PROPERTY MVCL_LENS_PLUGIN_TARGETS ${target})
    endif()
endfunction()

function(mvcl_add_static_lens target id)
    cmake_parse_arguments(PARSE_ARGV 2 arg "" "" "SOURCES")
    if(arg_UNPARSED_ARGUMENTS OR NOT arg_SOURCES)
        message(FATAL_ERROR "usage: mvcl_add_static_lens(<target> <id> SOURCES <file>...)")
    endif()
    if(NOT id MATCHES "^[A-Za-z_][A-Za-z0-9_]*$")
        message(FATAL_ERROR "mvcl_add_static_lens: '${id}' is not a C identifier (it names mvcl_lens_plugin_<id>)")
    endif()
    add_library(${target} OBJECT ${arg_SOURCES})
    target_link_libraries(${target} PUBLIC mvcl::mvcl)
    target_compile_features(${target} PUBLIC cxx_std_20)
    target_compile_definitions(${target} PRIVATE MVCL_LENS_STATIC_ID=${id})
endfunction()
