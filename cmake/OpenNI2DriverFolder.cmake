# A private OpenNI2 driver folder in the build tree.
# OpenNI2 loads its drivers from <folder of the loaded libOpenNI2.so.0>/OpenNI2/Drivers,
# so build/lib holds a link to the system libOpenNI2.so.0, links to the stock file and
# PS1080 drivers, and our virtual sensor. Executables find build/lib through an old-style
# RPATH, which also applies to libraries that link libOpenNI2 themselves (libpcl_io).
find_package(PkgConfig REQUIRED)
pkg_check_modules(OPENNI2 REQUIRED IMPORTED_TARGET libopenni2)
find_file(LCCP_SYSTEM_OPENNI2 libOpenNI2.so.0 PATHS ${OPENNI2_LIBRARY_DIRS} ${CMAKE_LIBRARY_ARCHITECTURE}
          PATH_SUFFIXES ${CMAKE_LIBRARY_ARCHITECTURE} REQUIRED)
get_filename_component(LCCP_SYSTEM_OPENNI2_DIR ${LCCP_SYSTEM_OPENNI2} DIRECTORY)

set(LCCP_OPENNI2_FOLDER ${CMAKE_BINARY_DIR}/lib)
set(LCCP_OPENNI2_DRIVERS ${LCCP_OPENNI2_FOLDER}/OpenNI2/Drivers)
file(MAKE_DIRECTORY ${LCCP_OPENNI2_DRIVERS})
file(CREATE_LINK ${LCCP_SYSTEM_OPENNI2} ${LCCP_OPENNI2_FOLDER}/libOpenNI2.so.0 SYMBOLIC)
foreach(driver OniFile PS1080)
  set(system_driver ${LCCP_SYSTEM_OPENNI2_DIR}/OpenNI2/Drivers/lib${driver}.so.0)
  if(EXISTS ${system_driver})
    file(CREATE_LINK ${system_driver} ${LCCP_OPENNI2_DRIVERS}/lib${driver}.so.0 SYMBOLIC)
  endif()
endforeach()

# Makes `target` (an executable or library whose file is `relative_path_to_lib` away
# from the folder: lib, ../lib, or .) load libOpenNI2 and its drivers from the private
# folder, in the build tree and, installed, from <prefix>/lib (relative, so a moved
# prefix keeps working).
function(lccp_use_openni2_folder target relative_path_to_lib)
  set_target_properties(${target} PROPERTIES BUILD_RPATH "$ORIGIN/${relative_path_to_lib}")
  target_link_options(${target} PRIVATE -Wl,--disable-new-dtags)
endfunction()
