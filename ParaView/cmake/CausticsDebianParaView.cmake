# Debian 12's ParaView 5.11 is split so that paraview-dev alone cannot build a
# plugin: python3-paraview holds ParaView's Python modules and pvpython (which
# paraview-dev's CMake package lists among its imported targets, and CMake refuses
# a package whose imported files are missing) and the wrapping hierarchy files
# of ParaView's VTK (which wrapping a plugin's classes for the server manager
# reads). But python3-paraview conflicts with python3-vtk9, which libvtk9-dev (the
# main build's VTK 9.1) depends on: the two cannot be installed together.
#
# So python3-paraview is unpacked, not installed, into CAUSTICS_PARAVIEW_PYTHON_ROOT
# (by default <build>/deps/python3-paraview, unpacked there by
# unpack-python3-paraview.sh with `apt-get download` and `dpkg-deb -x`), and this makes a copy of ParaView's CMake package
# in the build tree where the install prefix is pinned to the system's, the
# check of python3-paraview's files is dropped and the hierarchy files are read
# from the unpacked package. ParaView is then found in the copy.
set(CAUSTICS_PARAVIEW_PYTHON_ROOT "${CMAKE_BINARY_DIR}/deps/python3-paraview" CACHE PATH
  "Where python3-paraview is unpacked (dpkg-deb -x) when it is not installed")
set(caustics_debian_paraview_dir "/usr/lib/x86_64-linux-gnu/cmake/paraview-5.11")
if (ParaView_DIR OR NOT EXISTS "${caustics_debian_paraview_dir}/paraview-config.cmake" OR
    EXISTS "/usr/lib/python3/dist-packages/vtkmodules/vtkCommonCore.so")
  return ()
endif ()
set(caustics_paraview_hierarchy
  "${CAUSTICS_PARAVIEW_PYTHON_ROOT}/usr/lib/x86_64-linux-gnu/vtk/hierarchy")
if (NOT EXISTS "${caustics_paraview_hierarchy}/ParaView/vtkCommonCore-hierarchy.txt")
  execute_process(
    COMMAND "${CMAKE_CURRENT_LIST_DIR}/unpack-python3-paraview.sh" "${CAUSTICS_PARAVIEW_PYTHON_ROOT}"
    RESULT_VARIABLE caustics_unpack_result)
endif ()
if (NOT EXISTS "${caustics_paraview_hierarchy}/ParaView/vtkCommonCore-hierarchy.txt")
  message(FATAL_ERROR "Debian's python3-paraview is not installed (it conflicts with "
    "python3-vtk9, which libvtk9-dev needs) and CAUSTICS_PARAVIEW_PYTHON_ROOT "
    "('${CAUSTICS_PARAVIEW_PYTHON_ROOT}') holds no unpacked copy of it, and "
    "ParaView/cmake/unpack-python3-paraview.sh could not make one (exit ${caustics_unpack_result}).")
endif ()

set(caustics_paraview_copy "${CMAKE_BINARY_DIR}/paraview-cmake")
file(GLOB_RECURSE caustics_paraview_files RELATIVE "${caustics_debian_paraview_dir}"
  "${caustics_debian_paraview_dir}/*")
foreach (file IN LISTS caustics_paraview_files)
  get_filename_component(directory "${caustics_debian_paraview_dir}/${file}" DIRECTORY)
  file(READ "${caustics_debian_paraview_dir}/${file}" contents)
  # Targets and module properties find the install prefix from their own location.
  string(REPLACE "get_filename_component(_IMPORT_PREFIX \"\${CMAKE_CURRENT_LIST_FILE}\" PATH)"
    "set(_IMPORT_PREFIX \"${directory}\")" contents "${contents}")
  string(REPLACE "\${CMAKE_CURRENT_LIST_DIR}/../" "${directory}/../" contents "${contents}")
  string(REPLACE "set(_vtk_module_import_prefix \"\${CMAKE_CURRENT_LIST_DIR}\")"
    "set(_vtk_module_import_prefix \"${directory}\")" contents "${contents}")
  string(REPLACE "\${_vtk_module_import_prefix}/lib/x86_64-linux-gnu/vtk/hierarchy"
    "${caustics_paraview_hierarchy}" contents "${contents}")
  # The check of the files python3-paraview installs (modules, pvpython).
  string(REGEX REPLACE "list\\(APPEND _cmake_import_check_files_for_[^\n]*python[^\n]*\n" ""
    contents "${contents}")
  file(WRITE "${caustics_paraview_copy}/${file}" "${contents}")
endforeach ()
set(ParaView_DIR "${caustics_paraview_copy}" CACHE PATH
  "ParaView's CMake package (a patched copy; see ParaView/cmake/CausticsDebianParaView.cmake)"
  FORCE)
message(STATUS "ParaView: python3-paraview unpacked in ${CAUSTICS_PARAVIEW_PYTHON_ROOT}; "
  "ParaView's CMake package copied to ${caustics_paraview_copy}")
