#version 450 core
// Edge distance shadow map (Kenzel 2013): the silhouette edges of the frame's
// light, found once per light, for every face and edge pass that follows
// (render/src/silhouette_edges.cpp). One invocation per baked candidate edge
// of every caster (geom/esm_quads.h records, gathered into one buffer: both
// face planes), the silhouette test of Bujnak 2004, Sect. 3.1 (the light in
// front of one plane and behind the other; of a bevel or boundary edge's two
// records exactly one passes), and a stable compaction: the passing records'
// indices in record order, so the edge passes draw the same edges in the same
// order every frame. Records [u_first, u_first + u_count) at a time, their
// list from slot u_first; each invocation owns a run of kRun consecutive
// records, so no step needs a workgroup barrier (a software rasterizer such
// as llvmpipe runs barriers as coroutine switches, the cost of this pass).
// Three steps (u_step), each a dispatch, with a storage barrier between:
//   0  per run, its silhouette count into runs[]
//   1  one invocation: runs[] becomes its exclusive prefix sum, and the
//      indirect draw command u_command (glDrawArraysIndirect: 6 vertices per
//      silhouette edge, one instance) is written
//   2  per run again: each silhouette record's index at its slot
// Buffers (std430): 0 the records as they lie (9 uints each: p0, p1, plane_a,
// plane_b, q), 1 the commands (4 uints each), 2 the list, 3 runs[], 4 the
// caster of each record, 5 per caster its light in its local frame
// (homogeneous) and the index of its first plane in u_planes.
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Records { uint records[]; };
layout(std430, binding = 1) buffer Commands { uint commands[]; };
layout(std430, binding = 2) writeonly buffer Silhouettes { uint silhouettes[]; };
layout(std430, binding = 3) buffer Runs { uint runs[]; };
layout(std430, binding = 4) readonly buffer RecordCasters { uint record_caster[]; };
struct CasterLight {
  vec4 light;   // the light in the caster's local frame, homogeneous
  uvec4 first;  // x: its first plane in u_planes
};
layout(std430, binding = 5) readonly buffer CasterLights { CasterLight caster_lights[]; };
uniform int u_step;
uniform uint u_first;            // the first record of this dispatch, and its list's first slot
uniform uint u_count;            // its records
uniform uint u_command;          // its command's index
uniform samplerBuffer u_planes;  // every caster's planes (RGBA32F texture buffer)

const uint kFlip = 0x80000000u;
const uint kRun = 32u;  // records per invocation (render/src/silhouette_edges.cpp: kRun)

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

void main() {
  uint i = gl_GlobalInvocationID.x, n_runs = (u_count + kRun - 1u) / kRun;
  if (u_step == 1) {
    if (i != 0u) return;
    uint sum = 0u;
    for (uint k = 0u; k < n_runs; ++k) {
      uint c = runs[k];
      runs[k] = sum;
      sum += c;
    }
    uint c = 4u * u_command;
    commands[c] = 6u * sum;
    commands[c + 1u] = 1u;
    commands[c + 2u] = 0u;
    commands[c + 3u] = 0u;
    return;
  }
  if (i >= n_runs) return;
  uint begin = i * kRun, end = min(begin + kRun, u_count);
  if (u_step == 0) {
    uint count = 0u;
    for (uint k = begin; k < end; ++k) count += silhouette(k) ? 1u : 0u;
    runs[i] = count;
  } else {
    uint slot = u_first + runs[i];
    for (uint k = begin; k < end; ++k)
      if (silhouette(k)) silhouettes[slot++] = u_first + k;
  }
}
