// One point sprite per photon hit, sized to cover the photon's kernel disk on
// the receiver as the target view sees it.
// The landed photons (the photon record layout of vtkCausticsCommon.glsl).
uniform sampler2D hitPosition;  // xyz world, w > 0: a photon landed here
uniform sampler2D hitNormal;    // xyz receiver normal as modelled
uniform sampler2D hitFlux;      // rgb W
uniform sampler2D kernelRadius; // r: the kernel's radius (m)
uniform int hitWidth;
uniform mat4 worldToClip;
uniform vec2 viewport;
uniform float minimumRadiusPixels;
uniform float maximumRadiusPixels;

flat out vec3 splatCentre;
flat out vec3 splatNormal;
flat out vec3 splatFlux;
flat out float splatRadius;

void Discard()
{
  gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // outside the clip volume
  gl_PointSize = 1.0;
  splatRadius = 0.0;
}

vec2 ToPixels(vec3 p)
{
  vec4 clip = worldToClip * vec4(p, 1.0);
  return (clip.xy / clip.w * 0.5 + 0.5) * viewport;
}

void main()
{
  ivec2 texel = ivec2(gl_VertexID % hitWidth, gl_VertexID / hitWidth);
  vec4 position = texelFetch(hitPosition, texel, 0);
  vec3 normal = texelFetch(hitNormal, texel, 0).xyz;
  float radius = texelFetch(kernelRadius, texel, 0).r;
  vec3 flux = texelFetch(hitFlux, texel, 0).rgb;
  vec4 clip = worldToClip * vec4(position.xyz, 1.0);
  if (position.w <= 0.0 || clip.w <= 0.0 || dot(flux, vec3(1.0)) <= 0.0 ||
    !(radius > 0.0))
  {
    Discard();
    return;
  }
  vec3 n = normalize(normal);
  vec3 helper = abs(n.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  vec3 e1 = normalize(cross(n, helper));
  vec3 e2 = cross(n, e1);
  float r = radius;
  vec2 centre = ToPixels(position.xyz);
  // Projected radius along the two tangents; a tilted disk's ellipse fits in sqrt(2) x max.
  float pixels = max(length(ToPixels(position.xyz + r * e1) - centre),
    length(ToPixels(position.xyz + r * e2) - centre));
  if (!(pixels > 0.0))
  {
    Discard();
    return;
  }
  // Keep every kernel at least a few pixels wide (else it falls between pixel
  // centres and its energy is lost) and bounded in cost; the kernel stays
  // normalized for the radius actually used.
  float clamped = clamp(pixels, minimumRadiusPixels, maximumRadiusPixels);
  r *= clamped / pixels;
  splatCentre = position.xyz;
  splatNormal = n;
  splatFlux = flux;
  splatRadius = r;
  gl_Position = clip;
  gl_PointSize = min(2.0 * 1.4143 * clamped + 2.0, 1023.0);
}
