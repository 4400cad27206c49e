// Every ray becomes a horizontal line in its own row of the offscreen target,
// starting at the left column and covering n_f fragments (§2.1, Fig. 4). The ray
// ray and its line go to the fragments, which find their screen position from them.
SSP_RAYS(readonly);
SSP_LINES(readonly);

uniform int batchBase; // first ray of this batch
uniform vec2 target;   // row width, rows per batch

// The ray and its line, constant along the row (fetched once per line, not per fragment).
flat out SspRay lineRay;
flat out SspLine line;

void main()
{
  int ray = gl_VertexID / 2;
  int end = gl_VertexID % 2;
  lineRay = rays[ray];
  line = lines[ray];
  float n = line.info.x;
  if (!(n > 0.0))
  {
    gl_Position = vec4(2.0, 2.0, 0.0, 1.0); // nothing to trace: outside the viewport
    return;
  }
  // Quarter-pixel overshoot: every column's diamond is crossed (diamond-exit rule);
  // the fragment shader drops columns >= n_f.
  float x = end == 0 ? -0.25 : n + 0.25;
  float y = float(ray - batchBase) + 0.5;
  gl_Position = vec4(x / target.x * 2.0 - 1.0, y / target.y * 2.0 - 1.0, 0.0, 1.0);
}
