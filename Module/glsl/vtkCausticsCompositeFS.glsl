// Adds caustic light to VTK's image. VTK shades a Lambertian surface as
// albedo x intensity x cos, i.e. pi x radiance for irradiance in W/m^2, so the
// caustic term in the same display units is albedo x caustic irradiance.
// It is added only where the caustics G-buffer's receiver is what VTK drew
// (same depth), so props drawn by VTK alone are never painted over. A technique
// may replace VTK's colour where its own colour has alpha 1 (e.g. refractors
// seen through traced refraction), and add volume radiance (pi x, like surfaces).
// VTK shades receivers without shadows and without the medium: where reflectors and
// refractors block the light (which they pass on as the caustic) or the medium
// takes it on its way from the light, that part of VTK's diffuse shading is taken
// off first (lostShading, per unit albedo). With a medium, every surface is then
// dimmed by its transmittance towards the camera (the volume radiance already is).
in vec2 texCoord;

uniform sampler2D delegateColor;
uniform sampler2D delegateDepth;
uniform sampler2D gNormal;  // w = role
uniform sampler2D gAlbedo;
uniform sampler2D gDepth;
uniform sampler2D causticIrradiance;
uniform sampler2D volumeRadiance;
uniform sampler2D techniqueColor;
uniform sampler2D lostShading;
uniform int hasLostShading;
uniform int hasMedium;    // dim surfaces by the medium towards the camera
uniform mat4 clipToWorld; // the camera's
uniform int hasCaustics;
uniform int hasVolume;
uniform int hasTechniqueColor;
uniform float depthTolerance;

layout(location = 0) out vec4 outColor;

void main()
{
  vec4 color = texture(delegateColor, texCoord);
  float depth = texture(delegateDepth, texCoord).r;
  if (hasTechniqueColor != 0)
  {
    vec4 replacement = texture(techniqueColor, texCoord);
    if (replacement.a >= 1.0)
    {
      color.rgb = replacement.rgb;
    }
  }
  if (hasCaustics != 0)
  {
    int role = int(texture(gNormal, texCoord).w + 0.5);
    float surfaceDepth = texture(gDepth, texCoord).r;
    if (role == ROLE_RECEIVER && abs(surfaceDepth - depth) <= depthTolerance)
    {
      vec3 albedo = texture(gAlbedo, texCoord).rgb;
      if (hasLostShading != 0)
      {
        color.rgb = max(color.rgb - albedo * texture(lostShading, texCoord).rgb, vec3(0.0));
      }
      vec3 irradiance = texture(causticIrradiance, texCoord).rgb;
      color.rgb += albedo * max(irradiance, vec3(0.0));
    }
  }
  if (hasMedium != 0 && depth < 1.0)
  {
    vec2 ndc = 2.0 * texCoord - 1.0;
    vec4 near = clipToWorld * vec4(ndc, -1.0, 1.0);
    vec4 surface = clipToWorld * vec4(ndc, 2.0 * depth - 1.0, 1.0);
    vec3 from = near.xyz / near.w;
    color.rgb *= CausticsMediumTransmittanceToCamera(surface.xyz / surface.w, from);
  }
  if (hasVolume != 0)
  {
    color.rgb += CAUSTICS_PI * texture(volumeRadiance, texCoord).rgb;
  }
  outColor = color;
  gl_FragDepth = depth;
}
