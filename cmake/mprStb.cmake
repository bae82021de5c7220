# Defines the imported target mpr::stb for Debian's compiled stb (libstb-dev), if found.
# Used both by mpr's own build and by the installed mprConfig.cmake.
if(NOT TARGET mpr::stb)
  find_path(MPR_STB_INCLUDE_DIR stb_image.h PATH_SUFFIXES stb)
  find_library(MPR_STB_LIBRARY NAMES stb)
  if(MPR_STB_INCLUDE_DIR AND MPR_STB_LIBRARY)
    add_library(mpr::stb UNKNOWN IMPORTED)
    set_target_properties(mpr::stb PROPERTIES IMPORTED_LOCATION "${MPR_STB_LIBRARY}"
                                              INTERFACE_INCLUDE_DIRECTORIES "${MPR_STB_INCLUDE_DIR}")
  endif()
endif()
