#version 450 core
// Edge distance shadow map (Kenzel 2013): the silhouette edges of the frame's
// light, found once per light, for every face and edge pass that follows
// (render/src/silhouette_edges.cpp). One invocation per baked candidate edge
// of every caster (geom/esm_quads.h records, gathered into one buffer: both
// face planes), the silhouette test of Bujnak 2004, Sect. 3.1 (the light in
// front of one plane and behind the other; of a bevel or boundary edge's two
// records exactly one passes), and a stable compaction: the passing records'
// indices in record order, so the edge passes draw the same edges in the same
// order every frame. Records [u_first, u_first + u_count) at a time (at most
// 65535 workgroups), their list from slot u_first.
// Three steps (u_step), each a dispatch, with a storage barrier between:
//   0  per workgroup of 256 records, its silhouette count into groups[]
//   1  one workgroup: groups[] becomes its exclusive prefix sum, and the
//      indirect draw command u_command (glDrawArraysIndirect: 6 vertices per
//      silhouette edge, one instance) is written
//   2  per workgroup again: each silhouette record's index at its slot
// Buffers (std430): 0 the records as they lie (9 uints each: p0, p1, plane_a,
// plane_b, q), 1 the commands (4 uints each), 2 the list, 3 groups[], 4 the
// caster of each record, 5 per caster its light in its local frame
// (homogeneous) and the index of its first plane in u_planes.
layout(local_size_x = 256) in;
layout(std430, binding = 0) readonly buffer Records { uint records[]; };
layout(std430, binding = 1) buffer Commands { uint commands[]; };
layout(std430, binding = 2) writeonly buffer Silhouettes { uint silhouettes[]; };
layout(std430, binding = 3) buffer Groups { uint groups[]; };
layout(std430, binding = 4) readonly buffer RecordCasters { uint record_caster[]; };
struct CasterLight {
  vec4 light;   // the light in the caster's local frame, homogeneous
  uvec4 first;  // x: its first plane in u_planes
};
layout(std430, binding = 5) readonly buffer CasterLights { CasterLight caster_lights[]; };
uniform int u_step;
uniform uint u_first;            // the first record of this dispatch, and its list's first slot
uniform uint u_count;            // its records
uniform uint u_groups;           // its workgroups of steps 0 and 2
uniform uint u_command;          // its command's index
uniform samplerBuffer u_planes;  // every caster's planes (RGBA32F texture buffer)

const uint kFlip = 0x80000000u;
shared uint s_sum[256];

bool in_front(uint index, CasterLight c) {  // as shaders/esm_quad.vert
  vec4 p = texelFetch(u_planes, int(c.first.x + (index & 0x7fffffffu)));
  precise float s = p.x * c.light.x;
  s = s + p.y * c.light.y;
  s = s + p.z * c.light.z;
  s = s + p.w * c.light.w;
  return (s > 0.0) != ((index & kFlip) != 0u);
}

// Whether record u_first + i is a silhouette edge of the frame's light.
bool silhouette(uint i) {
  if (i >= u_count) return false;
  uint r = u_first + i;
  CasterLight c = caster_lights[record_caster[r]];
  return in_front(records[9u * r + 6u], c) != in_front(records[9u * r + 7u], c);
}

// s_sum becomes the inclusive prefix sum of the workgroup's values.
void scan(uint v) {
  uint t = gl_LocalInvocationID.x;
  s_sum[t] = v;
  barrier();
  for (uint d = 1u; d < 256u; d <<= 1) {
    uint add = t >= d ? s_sum[t - d] : 0u;
    barrier();
    s_sum[t] += add;
    barrier();
  }
}

void main() {
  uint t = gl_LocalInvocationID.x, g = gl_WorkGroupID.x, i = gl_GlobalInvocationID.x;
  if (u_step == 0) {
    scan(silhouette(i) ? 1u : 0u);
    if (t == 255u) groups[g] = s_sum[255];
  } else if (u_step == 1) {
    uint per = (u_groups + 255u) / 256u, begin = t * per, sum = 0u;
    for (uint k = 0u; k < per; ++k)
      if (begin + k < u_groups) sum += groups[begin + k];
    scan(sum);
    uint run = s_sum[t] - sum;
    for (uint k = 0u; k < per; ++k)
      if (begin + k < u_groups) {
        uint c = groups[begin + k];
        groups[begin + k] = run;
        run += c;
      }
    if (t == 255u) {
      uint c = 4u * u_command;
      commands[c] = 6u * s_sum[255];
      commands[c + 1u] = 1u;
      commands[c + 2u] = 0u;
      commands[c + 3u] = 0u;
    }
  } else {
    bool s = silhouette(i);
    scan(s ? 1u : 0u);
    if (s) silhouettes[u_first + groups[g] + s_sum[t] - 1u] = u_first + i;
  }
}
