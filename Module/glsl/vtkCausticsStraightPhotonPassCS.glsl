// Straight transport (vtkCausticsStraightPhotonPass): a photon that still travels
// along its light ray lands where that ray meets its first receiver, which the
// light's receiver-only G-buffer shows in the photon's own texel. Writes the landed
// photon records (vtkCausticsCommon.glsl) and their kernel radii; photons that
// turned (or found no receiver) get position.w = 0.
layout(local_size_x = 16, local_size_y = 16) in;

layout(rgba32f, binding = 0) uniform readonly image2D emitPosition;  // xyz, w = state (0: none)
layout(rgba32f, binding = 1) uniform readonly image2D emitDirection; // xyz, w = m^2 or sr
layout(rgba32f, binding = 2) uniform readonly image2D emitFlux;      // rgb W
layout(rgba32f, binding = 3) uniform readonly image2D receiverPosition; // w = material (-1: none)
layout(rgba16f, binding = 4) uniform readonly image2D receiverNormal;
uniform ivec2 grid;
uniform int resolution; // N: rows N..2N-1 are the Fresnel-reflected branch
uniform vec4 light;     // w = 0: direction of a directional light; w = 1: position
uniform vec3 viewEye;   // a point of the light view's eye plane (directional lights)
uniform float spacings;

layout(rgba32f, binding = 5) uniform writeonly image2D outPosition;
layout(rgba32f, binding = 6) uniform writeonly image2D outNormal;
layout(rgba32f, binding = 7) uniform writeonly image2D outFlux;
layout(r32f, binding = 8) uniform writeonly image2D outRadius;

void main()
{
  ivec2 t = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(t, grid)))
  {
    return;
  }
  vec4 p = imageLoad(emitPosition, t);
  vec4 d = imageLoad(emitDirection, t);
  ivec2 texel = ivec2(t.x, t.y % resolution);
  vec4 hit = imageLoad(receiverPosition, texel);
  vec3 n = normalize(imageLoad(receiverNormal, texel).xyz);
  vec3 ray = light.w == 0.0 ? light.xyz : normalize(p.xyz - light.xyz);
  if (p.w <= 0.0 || hit.w < 0.0 || dot(d.xyz, ray) < 0.9999)
  {
    imageStore(outPosition, t, vec4(0.0));
    return;
  }
  // Neighbouring photons lie sqrt(measure) apart across the beam (times the
  // distance for point lights), stretched by 1/cos on the receiver.
  float cosine = max(abs(dot(n, ray)), 1e-3);
  float distance = light.w == 0.0 ? 1.0 : length(hit.xyz - light.xyz);
  float path = max(light.w == 0.0 ? dot(hit.xyz - viewEye, light.xyz) : distance, 1e-6);
  imageStore(outPosition, t, vec4(hit.xyz, path));
  imageStore(outNormal, t, vec4(n, abs(dot(n, ray))));
  imageStore(outFlux, t, vec4(imageLoad(emitFlux, t).rgb, d.w));
  imageStore(outRadius, t, vec4(spacings * distance * sqrt(d.w / cosine)));
}
