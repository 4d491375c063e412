#version 450 core
// Inspection overlay: each line (a boundary, non-manifold or inconsistent
// edge, an edge of a degenerate face, an edge of the focus body) becomes a
// screen-space quad u_width pixels wide, its ends extended by half the width
// (a collapsed edge becomes a square dot), so that one-pixel lines never hide
// under the silhouette quads or the rasterizer's line rules.
//
// Depth: the quad keeps its edge's depth pulled towards the eye by the
// fraction u_depth_pull of the eye distance. With the camera's infinite
// perspective (z_ndc = 1 - 2n/d) that is z' = z - pull * (w - z) in clip
// space: the edge wins against the faces it lies on, while a wall in front
// still hides it (depth-tested).
//
// The segment is clipped to the near plane (z + w >= 0) before it is
// projected, so an edge passing behind the eye is drawn as its visible part.
layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;

uniform vec2 u_viewport;     // pixels
uniform float u_width;       // pixels
uniform float u_depth_pull;  // fraction of the eye distance, e.g. 0.004

void emit(vec4 p, vec2 offset_px) {
  vec4 q = p;
  q.xy += offset_px / (0.5 * u_viewport) * p.w;
  q.z = p.z - u_depth_pull * (p.w - p.z);
  gl_Position = q;
  EmitVertex();
}

void main() {
  vec4 a = gl_in[0].gl_Position, b = gl_in[1].gl_Position;
  float da = a.z + a.w, db = b.z + b.w;
  if (da < 0.0 && db < 0.0) return;
  if (da < 0.0) a = mix(a, b, da / (da - db));
  else if (db < 0.0) b = mix(b, a, db / (db - da));
  a.w = max(a.w, 1e-30);
  b.w = max(b.w, 1e-30);
  vec2 sa = a.xy / a.w * 0.5 * u_viewport, sb = b.xy / b.w * 0.5 * u_viewport;
  vec2 d = sb - sa;
  float len = length(d);
  vec2 dir = len > 1e-6 ? d / len : vec2(1.0, 0.0);
  vec2 n = vec2(-dir.y, dir.x) * (0.5 * u_width), t = dir * (0.5 * u_width);
  emit(a, -t - n);
  emit(a, -t + n);
  emit(b, t - n);
  emit(b, t + n);
  EndPrimitive();
}
