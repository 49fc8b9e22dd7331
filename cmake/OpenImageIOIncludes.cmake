# Debian 12's OpenImageIO config lists /usr/include/opencv4 among its include directories, which
# exists only when OpenCV is installed; pbrt_ext uses no OpenCV, so the path is dropped instead.
# Included by pbrt_ext's build and by its installed package config.
foreach(target OpenImageIO::OpenImageIO OpenImageIO::OpenImageIO_Util)
  if(TARGET ${target})
    get_target_property(dirs ${target} INTERFACE_INCLUDE_DIRECTORIES)
    if(dirs)
      list(FILTER dirs EXCLUDE REGEX "opencv")
      set_target_properties(${target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${dirs}")
    endif()
  endif()
endforeach()
