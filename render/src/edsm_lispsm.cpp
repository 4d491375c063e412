// edsm_lispsm.cpp: the edge distance shadow map drawn on LiSPSM's frustum
// (Kenzel 2013, Sect. 2 and 5.2: warping and edge reconstruction combine; a
// warp gives the near receivers more texels, the edges keep the far
// silhouettes exact). The light frame is geom/focus.h's LiSPSM matrix of the
// focus body H (Wimmer et al. 2004; light_fit.cpp chooses it for this
// technique), with its per-frame warp, eased or dropped where it would
// resolve a visible receiver more coarsely than the unwarped map. The passes
// are edsm's (edsm.cpp): LiSPSM's matrix is one projective map, so a
// silhouette edge stays a straight segment in the warped map and its line and
// depths are computed there, after the divide by w (shaders/edsm_quad.vert,
// edsm_edges.frag), as for a point light's perspective; the lookup,
// shaders/lookup_edsm.frag, projects the receiver with the same matrix. A
// point light that needs six faces gets edsm's faces.
#include "edge_pass.h"

namespace render {

bool edsm_lispsm_passes(Frame& f) {
  // edsm_passes lists the silhouette edges itself only for Technique::Edsm.
  return find_silhouettes(f) && edsm_passes(f);
}

}  // namespace render
