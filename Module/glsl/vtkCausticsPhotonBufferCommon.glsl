// Shared by the hierarchical caustic map stages (001_7c07a484f7a872bb.txt):
// vtkCausticsPhotonBuffer (photon tracing), vtkCausticsPhotonBufferHierarchy
// (validity mipmap, traversal, splat sizes) and vtkCausticsCausticMap (splats,
// final render). Buffer layouts here are mirrored on the host side in
// vtkCausticsPhotonBuffer.cxx and vtkCausticsPhotonBufferHierarchy.cxx.

// Their shader storage binding points: CAUSTICS_PHOTON_STATISTICS_BINDING and
// CAUSTICS_HIERARCHY_* in vtkCausticsBindings.h.

// Photon statistics (STAT_*): vtkCausticsPhotonStatistics.glsl.

// Hierarchy control block (uint words): indirect arguments and counters.
#define CONTROL_DISPATCH 0           // 3 words per traversal level, 16 levels
#define CONTROL_DRAW 48              // glDrawArraysIndirect arguments, 4 words per map level
#define CONTROL_LIST_COUNT 64        // items processed per traversal level (0 = photons)
#define CONTROL_VALID 80             // valid photons in the photon buffer
#define CONTROL_CLUSTERS 81          // clusters of converging photons splatted as one
#define CONTROL_CLUSTERED_PHOTONS 82 // photons inside those clusters
#define CONTROL_COARSE_SPLATS 83     // splats that needed caustic map level 4 or coarser
#define CONTROL_SPLAT_FLUX 84        // 64-bit flux splatted into map levels 0..3 (2 words each)
#define CONTROL_COARSE_FLUX 92       // 64-bit flux of the coarse splats
#define CONTROL_SIZE 96
#define MAX_TRAVERSAL_LEVELS 16

// A splat entry: photon index (y * width + x) in the low 28 bits, the cluster's
// mipmap level in the high 4 bits (0: a single photon).
#define SPLAT_INDEX_MASK 0x0FFFFFFFu
#define SPLAT_LEVEL_SHIFT 28u

// A light's view (caustics::LightView): orthographic along a directional light,
// perspective from a point or spot light.
struct CausticsView
{
  mat4 worldToClip;
  mat4 clipToWorld;
  vec3 eye;       // orthographic: a point of the eye plane
  vec3 axis;      // unit viewing direction
  vec2 size;      // pixels
  float texel;    // orthographic: texel width (m); perspective: texel width at unit depth
  int perspective;
};

// Continuous pixel coordinates of x (origin at the lower-left corner); false
// outside the view's frustum.
bool ViewProject(CausticsView v, vec3 x, out vec2 pixel)
{
  vec4 clip = v.worldToClip * vec4(x, 1.0);
  if (!(clip.w > 0.0))
  {
    pixel = vec2(-1.0);
    return false;
  }
  vec3 ndc = clip.xyz / clip.w;
  pixel = (ndc.xy * 0.5 + 0.5) * v.size;
  return all(greaterThanEqual(ndc, vec3(-1.0))) && all(lessThan(ndc, vec3(1.0)));
}

ivec2 ViewTexel(CausticsView v, vec2 pixel)
{
  return clamp(ivec2(floor(pixel)), ivec2(0), ivec2(v.size) - 1);
}

// Distance from the light along the texel's ray: what a depth buffer orders.
float ViewDepth(CausticsView v, vec3 x)
{
  return v.perspective != 0 ? length(x - v.eye) : dot(x - v.eye, v.axis);
}

// World width of one texel at x, across the view direction.
float ViewTexelSize(CausticsView v, vec3 x)
{
  return v.perspective != 0 ? v.texel * max(dot(x - v.eye, v.axis), 0.0) : v.texel;
}

// The direction light from this view travels at x.
vec3 ViewAway(CausticsView v, vec3 x)
{
  return v.perspective != 0 ? normalize(x - v.eye) : v.axis;
}

// Width (m) of a pixel's footprint on the surface (x, n) of camera view v: the
// square root of the pixel's area there (the pixel footprint of the reference's
// kernel), at most 1/sqrt(0.05) of the pixel's width at grazing view; 0 behind an
// orthographic view's eye plane or a perspective eye.
float CameraFootprint(CausticsView v, vec3 x, vec3 n)
{
  float cosine = abs(dot(n, ViewAway(v, x)));
  return ViewTexelSize(v, x) * inversesqrt(max(cosine, 0.05));
}

bool AllFinite(vec3 v)
{
  return !any(isnan(v)) && !any(isinf(v));
}

// Radius in pixels of view v covered by a disk of radius r (m) at x with normal n
// (the larger of its two projected tangent axes), as the splat vertex shaders size
// their point sprites; 0 if x is outside the view.
float ProjectedRadiusPixels(CausticsView v, vec3 x, vec3 n, float r)
{
  vec3 e1, e2;
  CausticsTangents(n, e1, e2);
  vec2 c, a, b;
  bool inside = ViewProject(v, x, c);
  ViewProject(v, x + r * e1, a);
  ViewProject(v, x + r * e2, b);
  return inside ? max(length(a - c), length(b - c)) : 0.0;
}
