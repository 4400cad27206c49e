# The module layering of issue 12, checked on what was built and on the sources:
# - the passes (VTK::RenderingCaustics) link neither Embree, OpenImageIO, jsoncpp nor
#   OpenVDB (the scene module reads density grids; the passes get NanoVDB from it),
#   and include none of them nor the I/O or reference classes;
# - the scene module links no OpenGL and none of the other caustics modules;
# - the reference (VTK::CausticsReference) does not depend on the passes.
# Run as: cmake -DREADELF=... -DPASSES=lib -DSCENE=lib -DREFERENCE=lib -DSOURCE=dir -P CheckLayering.cmake
set(failures "")

function (needed_libraries library out)
  execute_process(COMMAND "${READELF}" -d "${library}" OUTPUT_VARIABLE dynamic RESULT_VARIABLE rc)
  if (NOT rc EQUAL 0)
    message(FATAL_ERROR "layering: cannot read ${library} with ${READELF}")
  endif ()
  string(REGEX MATCHALL "Shared library: \\[[^]]+\\]" needed "${dynamic}")
  set(${out} "${needed}" PARENT_SCOPE)
endfunction ()

function (forbid what library pattern)
  needed_libraries("${library}" needed)
  foreach (entry IN LISTS needed)
    if (entry MATCHES "${pattern}")
      set(failures "${failures}\n  ${what} links ${entry}" PARENT_SCOPE)
    endif ()
  endforeach ()
endfunction ()

function (forbid_includes what directory pattern)
  file(GLOB files "${directory}/*.h" "${directory}/*.cxx")
  foreach (file IN LISTS files)
    file(STRINGS "${file}" lines REGEX "^#include")
    foreach (line IN LISTS lines)
      if (line MATCHES "${pattern}")
        get_filename_component(name "${file}" NAME)
        set(failures "${failures}\n  ${what}: ${name} has ${line}" PARENT_SCOPE)
      endif ()
    endforeach ()
  endforeach ()
endfunction ()

forbid("VTK::RenderingCaustics" "${PASSES}"
  "embree|OpenImageIO|jsoncpp|openvdb|vtkIOCaustics|vtkCausticsReference|vtkRenderingCausticsEGL|EGL")
forbid("VTK::CausticsScene" "${SCENE}" "libGL|EGL|OpenGL|vtkRenderingCaustics|vtkIOCaustics|vtkCausticsReference")
forbid("VTK::CausticsReference" "${REFERENCE}" "vtkRenderingCaustics|RenderingOpenGL2|libGL")

forbid_includes("passes" "${SOURCE}/Module"
  "embree|OpenImageIO|jsoncpp|vtkCausticsReference|vtkCausticsErrorMetrics|vtkCausticsImageIO|vtkCausticsGLTF|vtkCausticsMeshReader|vtkCausticsBuiltinScene|vtkCausticsEGL")
forbid_includes("scene" "${SOURCE}/Module/Scene" "vtkOpenGL|vtk_glew|vtkCausticsRenderPass|vtkCausticsShader|GLUtilities")
forbid_includes("reference" "${SOURCE}/Module/Reference"
  "vtkOpenGL|vtk_glew|vtkCausticsRenderPass|vtkCausticsShader|GLUtilities|PhotonPass|CausticMap")

if (failures)
  message(FATAL_ERROR "layering violated:${failures}")
endif ()
message(STATUS "layering: ok")
