# Finds the PLplot C library (Debian: libplplot-dev; PNG output needs plplot-driver-cairo).
# Debian's plplotConfig.cmake imports every language binding and driver and fails when they are
# not all installed, so this module uses pkg-config's plplot.pc instead.
# Defines the imported target PLplot::PLplot and PLplot_FOUND.
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  pkg_check_modules(PC_PLPLOT QUIET plplot)
endif()
find_path(PLplot_INCLUDE_DIR plplot.h HINTS ${PC_PLPLOT_INCLUDE_DIRS} PATH_SUFFIXES plplot)
find_library(PLplot_LIBRARY NAMES plplot HINTS ${PC_PLPLOT_LIBRARY_DIRS})
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(PLplot REQUIRED_VARS PLplot_LIBRARY PLplot_INCLUDE_DIR
                                  VERSION_VAR PC_PLPLOT_VERSION)
if(PLplot_FOUND AND NOT TARGET PLplot::PLplot)
  add_library(PLplot::PLplot UNKNOWN IMPORTED)
  set_target_properties(PLplot::PLplot PROPERTIES
    IMPORTED_LOCATION "${PLplot_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${PLplot_INCLUDE_DIR}")
endif()
mark_as_advanced(PLplot_INCLUDE_DIR PLplot_LIBRARY)
