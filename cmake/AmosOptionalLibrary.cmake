# amos_optional_library(<option> <target> NAME <name> PACKAGE <debian package> FEATURE <what it enables>
#                       LIBRARY <library path> INCLUDE_DIR <header folder> DOC <option text>)
# Declares the option <option>, on by default when LIBRARY and INCLUDE_DIR were found, and, when it is on, the
# imported target <target> with that library and header folder. The option on without the library is an error that
# names the Debian package to install.
function(amos_optional_library option target)
  cmake_parse_arguments(ARG "" "NAME;PACKAGE;FEATURE;LIBRARY;INCLUDE_DIR;DOC" "" ${ARGN})
  if(ARG_LIBRARY AND ARG_INCLUDE_DIR)
    set(found ON)
  else()
    set(found OFF)
  endif()
  option(${option} "${ARG_DOC}" ${found})
  if(NOT ${option})
    message(STATUS "${ARG_NAME}: ${ARG_FEATURE} off")
    return()
  endif()
  if(NOT found)
    message(FATAL_ERROR "${option}=ON but ${ARG_NAME} was not found (install ${ARG_PACKAGE})")
  endif()
  add_library(${target} INTERFACE IMPORTED)
  set_target_properties(${target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${ARG_INCLUDE_DIR}"
                                             INTERFACE_LINK_LIBRARIES "${ARG_LIBRARY}")
  message(STATUS "${ARG_NAME}: ${ARG_LIBRARY} (${ARG_FEATURE} on)")
endfunction()
