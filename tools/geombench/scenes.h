// tools/geombench/scenes.h: the scenes geombench measures, built in code (no
// big files committed) or read from Debian's data, each with its camera and
// light. The hard cases the papers name and the ones that break shadow maps:
//   default    data/default_scene.gltf with its own light
//   pipes      crossed pipes in front of a wall, point light (Bujnak 2004, its figure of crossing shadows)
//   jenga      9 towers of 55 levels of 3 blocks: 17,820 triangles (Kenzel 2013's jenga size)
//   heavy      a rippled sphere of 501,000 triangles over a ground (Kenzel 2013's phaeno size)
//   wide-depth a 400 m alley of pillars seen from one end, light perpendicular to the view
//              (Stamminger and Drettakis 2002, Fig. 1)
//   duelling   the same alley, light facing the camera ("duelling frusta", Stamminger and Drettakis 2002)
//   grazing    blocks on a ground, a directional light 3 degrees above the ground plane
//   scan       the Stanford bunny (a real scan, tests/data/draco/bunny_gltf.drc) on a ground
//   colonnade  a 200 m colonnade of round pillars seen from one end, a sun from the side (wide depth, lit from the
//   side) behind     the same colonnade, a point light behind and above the camera near-plane the default scene seen
//   with its near plane 6 units from the eye, inside a shadow (shadow volumes) quake3     OpenArena's oa_dm1 (Debian's
//   openarena-081-maps), a point light inside the level
#pragma once
#include <string>
#include <vector>

#include "geom/scene.h"

namespace geombench {

struct BenchScene {
  std::string name, description;
  geom::Scene scene;
  bool hard = false;         // one of the hard scenes (edsm against ssm)
  bool default_view = true;  // true: render::default_view of the scene
  geom::Camera view;         // else this camera (width / height set by the caller)
  geom::Light light;
};

// The scene of `name` (one of scene_names()); false with `error` set when its
// data is missing or does not import.
bool make_scene(const std::string& name, BenchScene& out, std::string& error);
std::vector<std::string> scene_names();        // the full run
std::vector<std::string> quick_scene_names();  // --quick

// A closed, rippled UV sphere of 2 n^2 + 2 n triangles with a seam column (as
// exported assets have): the mesh of the bake throughput table.
void add_sphere(geom::Scene& s, int n, float radius, const float centre[3]);

}  // namespace geombench
