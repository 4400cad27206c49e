// Flux carried by each light-space texel (W per channel) and its measure:
// solid angle (sr) for point/spot lights, area perpendicular to the light (m^2)
// for directional lights. Summed over the texels, the flux equals the light's
// power inside the frustum (vtkCausticsLightBuffers tests it within 0.5%).
uniform int perspective;
uniform vec2 halfExtent;     // along right and up: ortho, half width (m); perspective, tan(half angle)
uniform vec2 resolution;
uniform vec3 radiometric;    // W/m^2 (directional) or W/sr (point/spot)
uniform vec3 viewAxis;       // world direction of the frustum's centre
uniform vec3 viewRight;
uniform vec3 viewUp;
uniform int isSpot;
uniform vec3 spotAxis;
uniform float cosOuter;
uniform float cosInner;

layout(location = 0) out vec4 outFlux;

float SpotFactor(vec3 direction)
{
  return isSpot == 0 ? 1.0 : CausticsSpotFactor(dot(direction, spotAxis), cosOuter, cosInner);
}

void main()
{
  vec2 ndc = gl_FragCoord.xy / resolution * 2.0 - 1.0;
  vec2 texel = 2.0 * halfExtent / resolution;
  float measure;
  float spot = 1.0;
  if (perspective != 0)
  {
    // Solid angle of a texel on the image plane at distance 1: dA cos^3(theta),
    // midpoint rule (relative error ~1e-4 at 64^2 texels over 90 degrees).
    vec2 p = ndc * halfExtent;
    measure = texel.x * texel.y * pow(1.0 + dot(p, p), -1.5);
    spot = SpotFactor(normalize(viewAxis + p.x * viewRight + p.y * viewUp));
  }
  else
  {
    measure = texel.x * texel.y;
  }
  outFlux = vec4(radiometric * (measure * spot), measure);
}
