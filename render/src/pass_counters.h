// pass_counters.h (private to render/): the pipeline statistics queries
// (ARB_pipeline_statistics_query, core in GL 4.6) around one pass, read into a
// render::PassCounters (render/render.h). Kenzel 2013, Sect. 5.1 (figs. 5.3 and
// 5.4) reports primitives and pixel-shader invocations beside each algorithm's
// time: these are the same counts, hardware-independent where wall time is not.
#pragma once
#include "gl.h"

namespace render {

// True when the current context exposes the queries (GL 4.6 or the extension).
bool pass_counters_available();

// One pass's five queries: begin() before its draws, end() after, read() once
// the work is done (blocks until the results are there).
struct CounterQueries {
  Query queries[5];
  void begin();
  void end();
  PassCounters read() const;
};

}  // namespace render
