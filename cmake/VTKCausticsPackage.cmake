# The package configuration that find_package(VTKCaustics) reads, written into the
# build tree beside VTKCaustics-targets.cmake and installed with it. Included by the
# top-level CMakeLists.txt after vtk_module_build (and the Python wrapping).
#
# Inputs: caustics_modules (the modules built), caustics_cmake_destination,
# caustics_python_destination (empty without the wrapping).
include(CMakePackageConfigHelpers)

# caustics_component_needs(<module> <modules-var> <vtk-var>): the caustics modules
# <module> needs (itself included) and the VTK modules all of them link, public or
# private: a shared library's private VTK dependencies are still named by the
# exported targets (IMPORTED_LINK_DEPENDENT_LIBRARIES), so the user's project
# must have them as targets (VTK::jsoncpp needs the jsoncpp component).
function (caustics_component_needs module modules_var vtk_var)
  set(modules "${module}")
  set(vtk_components)
  set(index 0)
  list(LENGTH modules count)
  while (index LESS count)
    list(GET modules ${index} current)
    get_property(depends TARGET "${current}" PROPERTY INTERFACE_vtk_module_depends)
    get_property(private_depends TARGET "${current}" PROPERTY INTERFACE_vtk_module_private_depends)
    foreach (dependency IN LISTS depends private_depends)
      if (dependency IN_LIST caustics_modules)
        if (NOT dependency IN_LIST modules)
          list(APPEND modules "${dependency}")
        endif ()
      else ()
        string(REGEX REPLACE "^VTK::" "" dependency "${dependency}")
        list(APPEND vtk_components "${dependency}")
      endif ()
    endforeach ()
    math(EXPR index "${index} + 1")
    list(LENGTH modules count)
  endwhile ()
  list(REMOVE_DUPLICATES vtk_components)
  list(SORT vtk_components)
  string(REPLACE "VTK::" "" modules "${modules}")
  set(${modules_var} "${modules}" PARENT_SCOPE)
  set(${vtk_var} "${vtk_components}" PARENT_SCOPE)
endfunction ()

set(VTKCaustics_COMPONENTS)
set(VTKCaustics_COMPONENT_TABLE "# Per component: the modules it brings and the VTK components they link.\n")
foreach (caustics_module IN LISTS caustics_modules)
  caustics_component_needs("${caustics_module}" component_modules component_vtk)
  string(REPLACE "VTK::" "" component "${caustics_module}")
  list(APPEND VTKCaustics_COMPONENTS "${component}")
  string(REPLACE ";" " " component_modules "${component_modules}")
  string(REPLACE ";" " " component_vtk "${component_vtk}")
  string(APPEND VTKCaustics_COMPONENT_TABLE
    "set(_VTKCaustics_${component}_modules ${component_modules})\n"
    "set(_VTKCaustics_${component}_vtk ${component_vtk})\n")
endforeach ()
string(REPLACE ";" " " VTKCaustics_COMPONENTS "${VTKCaustics_COMPONENTS}")

file(RELATIVE_PATH VTKCaustics_CONFIG_TO_PREFIX
  "/prefix/${caustics_cmake_destination}" "/prefix")
set(VTKCaustics_PYTHON_DIR "${caustics_python_destination}")
set(VTK_VERSION_FOR_CONFIG "${VTK_VERSION_MAJOR}.${VTK_VERSION_MINOR}")

set(caustics_config_dir "${CMAKE_BINARY_DIR}/${caustics_cmake_destination}")
configure_file("${CMAKE_CURRENT_LIST_DIR}/VTKCausticsConfig.cmake.in"
  "${caustics_config_dir}/VTKCausticsConfig.cmake" @ONLY)
# 0.x: a minor version may change the API, so only the same minor version is compatible.
write_basic_package_version_file("${caustics_config_dir}/VTKCausticsConfigVersion.cmake"
  VERSION "${PROJECT_VERSION}" COMPATIBILITY SameMinorVersion)
install(FILES
  "${caustics_config_dir}/VTKCausticsConfig.cmake"
  "${caustics_config_dir}/VTKCausticsConfigVersion.cmake"
  DESTINATION "${caustics_cmake_destination}"
  COMPONENT   development)
