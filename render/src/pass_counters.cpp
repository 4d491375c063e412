// pass_counters.cpp: pipeline statistics per pass (pass_counters.h), and the
// sums over a frame's shadow passes (render/render.h).
#include "pass_counters.h"

#include <cstring>

namespace render {
namespace {

// The order of CounterQueries::queries and of the fields they fill.
constexpr GLenum kTargets[5] = {GL_PRIMITIVES_SUBMITTED_ARB, GL_VERTEX_SHADER_INVOCATIONS_ARB,
                                GL_GEOMETRY_SHADER_INVOCATIONS, GL_FRAGMENT_SHADER_INVOCATIONS_ARB,
                                GL_CLIPPING_OUTPUT_PRIMITIVES_ARB};

}  // namespace

bool pass_counters_available() {
  GLint major = 0, minor = 0, count = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major * 10 + minor >= 46) return true;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i) {
    const char* name = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
    if (name && std::strcmp(name, "GL_ARB_pipeline_statistics_query") == 0) return true;
  }
  return false;
}

void CounterQueries::begin() {
  for (int i = 0; i < 5; ++i) {
    // glGenQueries, not glCreateQueries: Mesa 22.3 refuses the statistics
    // targets there (GL_INVALID_ENUM); glBeginQuery makes the object.
    glGenQueries(1, &queries[i].id);
    glBeginQuery(kTargets[i], queries[i]);
  }
}

void CounterQueries::end() {
  for (int i = 0; i < 5; ++i) glEndQuery(kTargets[i]);
}

PassCounters CounterQueries::read() const {
  GLuint64 v[5] = {0, 0, 0, 0, 0};
  for (int i = 0; i < 5; ++i) glGetQueryObjectui64v(queries[i], GL_QUERY_RESULT, &v[i]);
  PassCounters c;
  c.valid = true;
  c.primitives = v[0], c.vs_invocations = v[1], c.gs_invocations = v[2], c.fs_invocations = v[3];
  c.clipping_primitives = v[4];
  return c;
}

PassCounters& PassCounters::operator+=(const PassCounters& o) {
  valid = valid || o.valid;
  primitives += o.primitives, vs_invocations += o.vs_invocations, gs_invocations += o.gs_invocations;
  fs_invocations += o.fs_invocations, clipping_primitives += o.clipping_primitives;
  return *this;
}

bool is_shadow_pass(const std::string& pass) {
  return pass != "depth + ambient" && pass != "lit shading" && pass != "shading" && pass != "inspection" &&
         pass.rfind("silhouette buffers", 0) != 0;
}

PassCounters shadow_counters(const std::vector<PassTime>& times) {
  PassCounters sum;
  for (const PassTime& t : times)
    if (is_shadow_pass(t.pass)) sum += t.counters;
  return sum;
}

}  // namespace render
