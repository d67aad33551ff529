# Optional USD export (`weft export cache.h5 --format usd OUT.usd`, io/usd_export.hpp) with OpenUSD's own Sdf
# library, from PyPI's C++ development wheels: pxr-sdf-dev and what it pulls (pxr-tf-dev, pxr-vt-dev, ...,
# pxr-boost-dev, pxr-tbb-dev). pip lays each out as <site-packages>/pxr-<lib>/{include,lib,cmake,pluginfo}
# (TBB as <site-packages>/TBB); scripts/setup.sh installs them. When found, weft_find_usd() defines the
# MODULE target weft_usd (io/usd/weft_usd.cpp -> bin/weft_usd.so, which weft loads only to export USD) and
# sets WEFT_USD_FOUND and WEFT_USD_MODULE (the module's path).
#   -DWEFT_USD=AUTO   USD export when the wheels are found (the default)
#   -DWEFT_USD=ON     fail when they are not
#   -DWEFT_USD=OFF    never
#   -DWEFT_USD_ROOT=DIR          a folder holding pxr-sdf/ (default: python3's site-packages)
#   -DPython_EXECUTABLE=PYTHON   the Python whose pip installed them (default: python3 on PATH)
set(WEFT_USD AUTO CACHE STRING "USD export with OpenUSD's Sdf (pxr-sdf-dev wheels): AUTO, ON or OFF")
set_property(CACHE WEFT_USD PROPERTY STRINGS AUTO ON OFF)
set(WEFT_USD_ROOT "" CACHE PATH "folder holding the pxr-* wheels' pxr-sdf/ (default: python3's site-packages)")

function(_weft_usd_missing why)
  if(WEFT_USD STREQUAL "ON")
    message(FATAL_ERROR "WEFT_USD=ON, but ${why}")
  endif()
  message(STATUS "USD export: off (${why}; scripts/setup.sh installs the pxr-sdf-dev wheel)")
endfunction()

function(weft_find_usd)
  set(WEFT_USD_FOUND FALSE PARENT_SCOPE)
  if(WEFT_USD STREQUAL "OFF")
    message(STATUS "USD export: off (WEFT_USD=OFF)")
    return()
  endif()

  # The wheels' Python: its site-packages hold them, and their libraries need its libpython (they leave it
  # to the Python that loads them; weft_usd.so links it). The real interpreter, not a pyenv shim.
  if(NOT Python_EXECUTABLE)
    find_program(WEFT_PYTHON NAMES python3)
    if(NOT WEFT_PYTHON)
      _weft_usd_missing("no python3")
      return()
    endif()
    execute_process(COMMAND ${WEFT_PYTHON} -c "import sys; print(sys.executable)"
                    OUTPUT_VARIABLE _exe OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    if(NOT _exe)
      _weft_usd_missing("${WEFT_PYTHON} does not run")
      return()
    endif()
    set(Python_EXECUTABLE ${_exe} CACHE FILEPATH "Python whose site-packages hold the OpenUSD wheels")
  endif()
  set(_roots ${WEFT_USD_ROOT})
  if(NOT _roots)
    execute_process(
      COMMAND ${Python_EXECUTABLE} -c "import site, sysconfig; p = sysconfig.get_paths(); \
print(';'.join([p['purelib'], p['platlib'], site.getusersitepackages()]))"
      OUTPUT_VARIABLE _roots OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  endif()
  set(_prefix "")
  foreach(d IN LISTS _roots)
    if(EXISTS "${d}/pxr-sdf/cmake/pxr-sdf/pxr-sdf-config.cmake")
      set(_prefix "${d}")
      break()
    endif()
  endforeach()
  if(NOT _prefix)
    _weft_usd_missing("no pxr-sdf-dev wheel under ${_roots}")
    return()
  endif()

  find_package(Python COMPONENTS Interpreter Development QUIET)
  if(NOT Python_Development_FOUND)
    _weft_usd_missing("${Python_EXECUTABLE} has no headers or libpython, which the OpenUSD wheels need")
    return()
  endif()
  # Each wheel's CMake package, and the TBB the wheels were built with rather than any other one.
  file(GLOB _configs "${_prefix}/pxr-*/cmake/pxr-*/pxr-*-config.cmake")
  foreach(c IN LISTS _configs)
    get_filename_component(_dir "${c}" DIRECTORY)
    get_filename_component(_name "${_dir}" NAME)
    set(${_name}_DIR "${_dir}")
  endforeach()
  if(EXISTS "${_prefix}/TBB/cmake/TBB/TBBConfig.cmake")
    set(TBB_DIR "${_prefix}/TBB/cmake/TBB")
  endif()
  find_package(pxr-sdf CONFIG QUIET)
  if(NOT pxr-sdf_FOUND OR NOT TARGET pxr::sdf)
    _weft_usd_missing("the pxr-sdf CMake package under ${_prefix} did not load")
    return()
  endif()

  # Plug (which Sdf asks for its file formats, and Ar for its resolver) reads plugInfo.json files. The
  # wheels' name their library at ../../.libs/, a layout the dev wheels do not install, and Plug does not
  # look where they are: copy each, naming the library where it is, for weft_usd.so to register.
  set(_plugins "${CMAKE_BINARY_DIR}/bin/weft_usd_plugins")
  file(REMOVE_RECURSE "${_plugins}")
  file(GLOB _infos "${_prefix}/pxr-*/pluginfo/*/resources/plugInfo.json")
  foreach(info IN LISTS _infos)
    string(REGEX MATCH "/(pxr-[^/]+)/pluginfo/([^/]+)/resources/plugInfo.json$" _m "${info}")
    set(_pkg "${CMAKE_MATCH_1}")
    set(_plugin "${CMAKE_MATCH_2}")
    file(READ "${info}" _json)
    string(REGEX MATCH "\"LibraryPath\" *: *\"[^\"]*\"" _lp "${_json}")
    string(REGEX REPLACE ".*\"([^\"]*)\"$" "\\1" _lib "${_lp}")
    get_filename_component(_lib "${_lib}" NAME)
    if(_lib AND EXISTS "${_prefix}/${_pkg}/lib/${_lib}")
      string(REGEX REPLACE "\"LibraryPath\" *: *\"[^\"]*\"" "\"LibraryPath\": \"${_prefix}/${_pkg}/lib/${_lib}\""
             _json "${_json}")
    endif()
    file(WRITE "${_plugins}/${_plugin}/resources/plugInfo.json" "${_json}")
  endforeach()

  add_library(weft_usd MODULE ${PROJECT_SOURCE_DIR}/io/usd/weft_usd.cpp)
  target_include_directories(weft_usd PRIVATE ${PROJECT_SOURCE_DIR})
  target_link_libraries(weft_usd PRIVATE pxr::sdf pxr::work Python::Python)
  target_compile_definitions(weft_usd PRIVATE WEFT_USD_PLUGINFO="${_plugins}")
  target_compile_options(weft_usd PRIVATE -Wno-deprecated)  # pxr/tf/hashset.h includes <ext/hash_set>
  # The wheels' libraries carry no run path to one another (pip's layout puts each in its own lib/): an
  # old-style RPATH, searched for every library the module pulls in and not only its own, holding each
  # wheel's lib/ folder and libpython's (CMake's build RPATH, from the imported targets).
  target_link_options(weft_usd PRIVATE "LINKER:--disable-new-dtags")
  set_target_properties(weft_usd PROPERTIES PREFIX "" LIBRARY_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/bin
                                            CXX_VISIBILITY_PRESET hidden)

  message(STATUS "USD export: on (OpenUSD Sdf ${pxr-sdf_VERSION} from ${_prefix}, Python ${Python_VERSION})")
  set(WEFT_USD_FOUND TRUE PARENT_SCOPE)
  set(WEFT_USD_MODULE "${CMAKE_BINARY_DIR}/bin/weft_usd.so" PARENT_SCOPE)
endfunction()
