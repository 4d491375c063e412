#version 450 core
// Stencil shadow volumes from the static records of geom/shadow_volume.h,
// extruded to infinity (w = 0) per light. The CPU reference is
// libgeom/src/extrude.cpp (side_corners, cap_corners): the same math, in the
// same order (`precise` keeps the plane test free of fused multiply-adds).
//
// Draws (one instance per record, vertex attribute divisor 1, no index buffer):
//   sides  u_caps = false  glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, n)
//          record SvSide, stride 32: p0 (loc 0), p1 (loc 1), plane_a (loc 3),
//          plane_b (loc 4); location 2 unused.
//   caps   u_caps = true   glDrawArraysInstanced(GL_TRIANGLES, 0, 6, n)
//          record SvCap, stride 40: a (loc 0), b (loc 1), c (loc 2), plane (loc 3);
//          location 4 unused.
// Depth-fail: sides + caps; depth-pass: sides only.
//
// GL state an engine sets (render/src/shadow_volume.cpp does exactly this):
//   - The scene's depth is in the depth buffer first, drawn with
//     glEnable(GL_POLYGON_OFFSET_FILL); glPolygonOffset(0.0, -8.0): the
//     receivers pulled 8 units of the depth buffer's resolution TOWARDS the
//     camera (negative units). Why: each near cap lies exactly on its lit face,
//     and side quads start on the faces' edges, so without it a surface is
//     shadowed by its own cap wherever rounding puts the cap in front
//     (a fifth of the pixels of data/default_scene.gltf: examples/engine_sample
//     --no-offset); moreover the volumes are drawn in
//     the local frame (u_view_proj includes the frame's origin) while the
//     scene is drawn in input coordinates, so the two depths of one point
//     differ by float rounding of the translation. The offset is constant
//     (factor 0): a slope term would also push grazing receivers out of volumes
//     that really contain them. Keep the same offset in the lit pass that
//     reads the stencil with glDepthFunc(GL_EQUAL), and none while drawing volumes.
//   - While drawing volumes: glDepthMask(GL_FALSE), glColorMask all GL_FALSE,
//     glDepthFunc(GL_LESS), face culling off (both faces are counted),
//     glEnable(GL_STENCIL_TEST), glStencilFunc(GL_ALWAYS, 0, 0xff),
//     glStencilMask(0xff), a stencil buffer of 8 bits (DEPTH24_STENCIL8), cleared to 0.
//   - Depth-fail (camera possibly inside a volume):
//       glStencilOpSeparate(GL_BACK,  GL_KEEP, GL_INCR_WRAP, GL_KEEP);
//       glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_DECR_WRAP, GL_KEEP);
//     depth-pass (camera outside every volume):
//       glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_KEEP, GL_INCR_WRAP);
//       glStencilOpSeparate(GL_BACK,  GL_KEEP, GL_KEEP, GL_DECR_WRAP);
//     with counter-clockwise front faces (GL's default glFrontFace(GL_CCW)).
//   - The far corners lie at infinity (w = 0): the camera projection must not
//     clip them. Either an infinite far plane (Arneson, Sect. 4.1: the limit of
//     the GL projection as far -> infinity) or glEnable(GL_DEPTH_CLAMP) during
//     the volume draws (what the viewer does; its projection is infinite too).
//   - Then lit shading where the count is zero: glStencilFunc(GL_EQUAL, 0, 0xff),
//     glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP), glDepthFunc(GL_EQUAL), the offset above.
// Uniforms:
//   mat4 u_view_proj          local frame (geom/face_planes.h) -> camera clip space:
//                             the camera's view-projection times a translation by
//                             the baked file's `frame` origin (local = input - origin)
//   vec4 u_light              the light in the local frame: (x, y, z, 1) a point
//                             light, (x, y, z, 0) a directional light lying at
//                             infinity towards (x, y, z); from input coordinates
//                             (x, y, z, w) as (x - w ox, y - w oy, z - w oz, w)
//                             (geom/extrude.h to_local_light)
//   bool u_caps               which record kind this draw reads
//   samplerBuffer u_planes    the volume's `planes`, an RGBA32F texture buffer
//                             (texture unit set by the application)
layout(location = 0) in vec3 a_p0;
layout(location = 1) in vec3 a_p1;
layout(location = 2) in vec3 a_p2;
layout(location = 3) in uint a_plane_a;
layout(location = 4) in uint a_plane_b;

uniform mat4 u_view_proj;
uniform vec4 u_light;
uniform bool u_caps;
uniform samplerBuffer u_planes;

const uint kFlag = 0x80000000u;
// Direction of a corner that lies on the light itself (no direction of its own);
// a guard: every record through a vertex at the light collapses (faces on the light).
const vec3 kAtLight = vec3(0.0, 0.0, -1.0);

// +1 light in front of the plane, 0 on it (within kOnLight of the terms' scale),
// -1 behind; geom::light_side in geom/shadow_volume.h.
const float kOnLight = 2e-6;
int light_side(uint index) {
  vec4 p = texelFetch(u_planes, int(index & 0x7fffffffu));
  precise float s = p.x * u_light.x;
  s = s + p.y * u_light.y;
  s = s + p.z * u_light.z;
  s = s + p.w * u_light.w;
  precise float m = abs(p.x * u_light.x);
  m = m + abs(p.y * u_light.y);
  m = m + abs(p.z * u_light.z);
  m = m + abs(p.w * u_light.w);
  m = m * kOnLight;
  return s > m ? 1 : (s < -m ? -1 : 0);
}

vec4 far_corner(vec3 v) {
  vec3 d = v * u_light.w - u_light.xyz;
  if (d == vec3(0.0)) d = kAtLight;
  return vec4(d, 0.0);
}

void main() {
  int k = gl_VertexID;
  vec4 corner;
  if (!u_caps) {
    // first copy and single records: front or not; second copy of a
    // double-sided pair (kFlag in plane_a): behind or not (geom/shadow_volume.h)
    int sa = light_side(a_plane_a);
    int sb = light_side(a_plane_b);
    if ((a_plane_b & kFlag) != 0u) sb = -sb;
    bool second_copy = (a_plane_a & kFlag) != 0u;
    bool fa = second_copy ? sa >= 0 : sa > 0;
    bool fb = second_copy ? sb >= 0 : sb > 0;
    if (fa == fb) {
      corner = vec4(a_p0, 1.0);  // the whole instance collapses to one point
    } else {
      vec3 a = fa ? a_p1 : a_p0;
      vec3 b = fa ? a_p0 : a_p1;
      vec3 v = (k & 1) == 0 ? a : b;
      corner = k < 2 ? vec4(v, 1.0) : far_corner(v);
    }
  } else {
    int side = light_side(a_plane_a);
    bool front = side > 0;
    bool double_sided = (a_plane_a & kFlag) != 0u;
    if (side == 0 || (!front && !double_sided)) {
      corner = vec4(a_p0, 1.0);
    } else {
      vec3 second = front ? a_p1 : a_p2;
      vec3 third = front ? a_p2 : a_p1;
      // near cap: a, second, third; far cap: a, third, second at infinity
      int j = k < 3 ? k : k - 3;
      vec3 v = j == 0 ? a_p0 : ((j == 1) == (k < 3) ? second : third);
      corner = k < 3 ? vec4(v, 1.0) : far_corner(v);
    }
  }
  gl_Position = u_view_proj * corner;
}
