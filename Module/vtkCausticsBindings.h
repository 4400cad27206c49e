// Shader storage binding points of every caustics stage: one table read by the
// host (glBindBufferBase) and by the shaders (layout(binding = ...)), as Falcor
// keeps its host/shader constants. The same file is a C++ header and GLSL
// source: vtkCausticsShaderProgram prepends it to every shader (embedded by
// Module/CMakeLists.txt as vtkCausticsBindingsSource), so it may hold only
// preprocessor lines that both languages accept (#ifndef/#define/#endif and
// // comments; no #pragma once, no C++ types, no double underscores).
// Internal: not installed, include it only from .cxx files.
//
// Binding points are per draw or dispatch, so stages that never run together
// reuse numbers (1 is the layered depth table of the screen-space stages and the
// photon statistics of the hierarchical caustic map stages). Image units
// (layout(rgba32f, binding = n) image2D) are a separate namespace, not listed.

#ifndef vtkCausticsBindings_h
#define vtkCausticsBindings_h

// Every stage: the material table (vtkCausticsSceneGeometry, vtkCausticsCommon.glsl).
#define CAUSTICS_MATERIAL_BINDING 0

// Screen-space photon tracing (vtkCausticsScreenSpaceCommon.glsl).
// Layered depth image (vtkCausticsLayeredDepth).
#define CAUSTICS_LDI_TABLE_BINDING 1
#define CAUSTICS_LDI_OBJECT_MAP_BINDING 2
#define CAUSTICS_LDI_COMMAND_INFO_BINDING 3
#define CAUSTICS_LDI_DRAW_COMMAND_BINDING 4
#define CAUSTICS_LDI_CLEAR_COMMAND_BINDING 5
// Rays of this bounce and their lines, hits and count (vtkCausticsScreenSpaceLineTracer).
#define CAUSTICS_SSP_RAY_BINDING 6
#define CAUSTICS_SSP_PAYLOAD_BINDING 7
#define CAUSTICS_SSP_LINE_BINDING 8
#define CAUSTICS_SSP_HIT_BINDING 9
#define CAUSTICS_SSP_COUNTER_BINDING 10
// Rays of the next bounce (vtkCausticsScreenSpacePhotonPass transfer).
#define CAUSTICS_SSP_NEXT_RAY_BINDING 11
#define CAUSTICS_SSP_NEXT_PAYLOAD_BINDING 12
#define CAUSTICS_SSP_NEXT_COUNTER_BINDING 13
// Indirect dispatch arguments of the line tracer.
#define CAUSTICS_SSP_ARGUMENT_BINDING 15

// Every stage that follows a heterogeneous medium: its NanoVDB density grid
// (caustics::gl::MediumBuffer; PNanoVDB.h reads it, vtkCausticsShaderProgram).
#define CAUSTICS_MEDIUM_GRID_BINDING 14

// Line-based volume caustics (vtkCausticsVolumeLines, glsl/vtkCausticsVolumeLinesCommon.glsl):
// the techniques' segments, their optical depths, the segment count and the lines' draw.
#define CAUSTICS_VOLUME_SEGMENT_BINDING 1
#define CAUSTICS_VOLUME_DEPTH_BINDING 2
#define CAUSTICS_VOLUME_COUNT_BINDING 3
#define CAUSTICS_VOLUME_ARGUMENT_BINDING 4
// A tracer appending its segments (CausticsAppendVolumeSegment, vtkCausticsVolumeSegmentList):
// past every binding the tracers use themselves.
#define CAUSTICS_VOLUME_APPEND_SEGMENT_BINDING 16
#define CAUSTICS_VOLUME_APPEND_COUNT_BINDING 17

// SVGF denoiser's reprojection (vtkCausticsSVGFReprojectCS.glsl): per mesh, the motion
// from this frame's world position to the last frame's and the mesh's last index.
#define CAUSTICS_SVGF_MOTION_BINDING 1

// Hierarchical caustic map (vtkCausticsPhotonBufferCommon.glsl).
#define CAUSTICS_PHOTON_STATISTICS_BINDING 1
#define CAUSTICS_HIERARCHY_NODES_BINDING 2
// Control words; the photon trace keeps its work lists here too.
#define CAUSTICS_HIERARCHY_CONTROL_BINDING 3
#define CAUSTICS_HIERARCHY_WORK_BINDING 4
#define CAUSTICS_HIERARCHY_SPLATS_BINDING 5

// The camera view of glass and mirrors (vtkCausticsSpecularHierarchy,
// glsl/vtkCausticsSpecularTrace.glsl): the specular triangles' hierarchy.
#define CAUSTICS_SPECULAR_NODE_BINDING 18
#define CAUSTICS_SPECULAR_TRIANGLE_BINDING 19

// Image units (a namespace of their own): the distance impostors' caustic store
// (vtkCausticsDistanceImpostors::BeginCaustic, glsl/vtkCausticsImpostorCommon.glsl).
#define CAUSTICS_IMPOSTOR_CAUSTIC_IMAGE 7

#endif
